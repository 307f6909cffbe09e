// Happens-before edges that ThreadSanitizer cannot see through uninstrumented libraries (Embree).
#pragma once

// Embree and oneTBB are Debian shared libraries built without ThreadSanitizer, so the ordering
// they give is invisible to it: Embree's build threads call prism's sphere-bounds callback
// after the spheres were written and before rtcCommitScene returns, but nothing it can see says
// so. prism marks those edges itself; in every other build these compile to nothing. (prism's
// own parallel loops run on std::threads in ThreadSanitizer builds: parallel_ranges.h.)
#if defined(__SANITIZE_THREAD__)
#define PRISM_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define PRISM_TSAN 1
#endif
#endif

#ifdef PRISM_TSAN
extern "C" void __tsan_acquire(void* addr);
extern "C" void __tsan_release(void* addr);
#endif

namespace prism {

// Everything this thread did before tsan_release(a) happens before what a thread does after a
// later tsan_acquire(a).
inline void tsan_release([[maybe_unused]] void* address) {
#ifdef PRISM_TSAN
  __tsan_release(address);
#endif
}
inline void tsan_acquire([[maybe_unused]] void* address) {
#ifdef PRISM_TSAN
  __tsan_acquire(address);
#endif
}

}  // namespace prism
