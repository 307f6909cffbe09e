// Process exit codes of the prism command line, one per class of failure.
#pragma once

namespace prism {

enum ExitCode : int {
  kExitOk = 0,
  kExitInternal = 1,  // a bug or an unexpected failure inside prism
  kExitUsage = 2,     // bad command-line arguments or settings
  kExitInput = 3,     // a scene, job file or image that cannot be used
  kExitOutput = 4,    // an output that cannot be written
  kExitThreshold = 5, // `prism compare --threshold`: the image misses it
  kExitStopped = 6,   // a render stopped by SIGINT or SIGTERM: its output holds what was rendered, resumable
  kExitMemory = 7,    // the work would need more memory than --memory-limit (estimated before allocating)
  kExitFarmFailed = 8,   // prism farm: Slurm refused a submission, or a task or the merge failed
  kExitFarmPending = 9,  // prism farm status: not finished yet (not submitted, pending or running)
};

}  // namespace prism
