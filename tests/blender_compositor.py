# Opens a prism EXR in Blender's compositor and checks what Blender sees: the layers the Image node
# offers, and Cryptomatte mattes picked by object name (Blender hashes the names itself) that add
# up to the alpha channel. Run: blender -b --factory-startup --python-exit-code 1 --python THIS --
#   IMAGE.exr WIDTH HEIGHT WORK_DIR OBJECT_NAME...
import sys

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
image_path, width, height, work, names = args[0], int(args[1]), int(args[2]), args[3], args[4:]

image = bpy.data.images.load(image_path)
scene = bpy.context.scene
# The compositor runs after a render: make that render as cheap as can be.
scene.render.engine = "CYCLES"
scene.cycles.samples = 1
scene.render.resolution_percentage = 100
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "32"
scene.use_nodes = True
tree = scene.node_tree
for node in list(tree.nodes):
    tree.nodes.remove(node)
source = tree.nodes.new("CompositorNodeImage")
source.image = image
# A multilayer image reports no size before the compositor reads it: the caller gives it.
scene.render.resolution_x, scene.render.resolution_y = width, height
composite = tree.nodes.new("CompositorNodeComposite")

layers = [output.name for output in source.outputs]
print("BLENDER image type:", image.type)
print("BLENDER layers:", ", ".join(layers))
expected = ["Combined", "Alpha", "Depth", "N", "P", "albedo", "emission", "direct", "indirect", "variance", "spp",
            "object_id", "material_id", "CryptoObject00", "CryptoMaterial00"]
missing = [name for name in expected if name not in layers]
if missing:
    raise SystemExit("Blender does not see the layers " + ", ".join(missing))


def composite_of(output, index):
    """Renders with `output` wired to the Composite node; returns the written image's red channel."""
    for link in list(tree.links):
        tree.links.remove(link)
    tree.links.new(output, composite.inputs[0])
    scene.render.filepath = f"{work}/composite{index}.exr"
    bpy.ops.render.render(write_still=True)
    result = bpy.data.images.load(scene.render.filepath)
    return list(result.pixels)[0::4]


alpha = composite_of(source.outputs["Alpha"], 0)
total = [0.0] * len(alpha)
for index, name in enumerate(names, start=1):
    matte_node = tree.nodes.new("CompositorNodeCryptomatteV2")
    matte_node.source = "IMAGE"
    matte_node.image = image
    matte_node.layer_name = "CryptoObject"
    matte_node.matte_id = name
    tree.links.new(source.outputs[0], matte_node.inputs[0])
    matte = composite_of(matte_node.outputs["Matte"], index)
    tree.links.new(source.outputs[0], matte_node.inputs[0])
    covered = sum(matte)
    print(f"BLENDER Cryptomatte matte '{name}': {covered:.1f} pixels of coverage")
    if covered <= 0:
        raise SystemExit(f"Blender's Cryptomatte node found no coverage for object '{name}'")
    total = [t + m for t, m in zip(total, matte)]

worst = max(abs(t - a) for t, a in zip(total, alpha))
print(f"BLENDER the {len(names)} object mattes add up to alpha within {worst:.2e} "
      f"(alpha covers {sum(alpha):.1f} pixels)")
if worst > 1e-4:
    raise SystemExit("the object mattes do not add up to alpha")
print("BLENDER PASS")
