# A path-traced reference for docs/material-truth.md ("Against a path tracer"): a unit sphere in a
# glTF-like metal under an environment, Cycles on the CPU, orthographic, 200², no denoising.
#   blender -b -P scripts/cycles-sphere.py -- ENV.exr ROUGHNESS OUT.exr [SAMPLES]
# Blender is Z-up: a direction (x, y, z) here is (x, z, −y) in mipgloss's frame (Y up), and this
# camera (at −Y looking +Y) is mipgloss's yaw 0, pitch 0 (`mipgloss render --yaw 0 --pitch 0`).
import bpy, sys, math
argv = sys.argv[sys.argv.index("--") + 1:]
env, rough, out = argv[0], float(argv[1]), argv[2]
samples = int(argv[3]) if len(argv) > 3 else 64
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.render.engine = 'CYCLES'
scene.cycles.device = 'CPU'
scene.cycles.samples = samples
scene.cycles.use_denoising = False
scene.render.resolution_x = scene.render.resolution_y = 200
scene.render.image_settings.file_format = 'OPEN_EXR'
scene.view_settings.view_transform = 'Standard'
world = bpy.data.worlds.new("w"); scene.world = world; world.use_nodes = True
nt = world.node_tree; bg = nt.nodes['Background']
tex = nt.nodes.new('ShaderNodeTexEnvironment'); tex.image = bpy.data.images.load(env)
nt.links.new(tex.outputs['Color'], bg.inputs['Color'])
bpy.ops.mesh.primitive_uv_sphere_add(segments=128, ring_count=64, radius=1.0)
obj = bpy.context.active_object; bpy.ops.object.shade_smooth()
mat = bpy.data.materials.new("m"); mat.use_nodes = True
p = mat.node_tree.nodes['Principled BSDF']
p.distribution = 'GGX'  # single scattering, as the glTF BRDF
p.inputs['Base Color'].default_value = (0.95, 0.64, 0.54, 1)
p.inputs['Metallic'].default_value = 1.0
p.inputs['Roughness'].default_value = rough
obj.data.materials.append(mat)
cam = bpy.data.cameras.new("c"); cam.type = 'ORTHO'; cam.ortho_scale = 2.1
co = bpy.data.objects.new("c", cam); scene.collection.objects.link(co); scene.camera = co
co.location = (0, -5, 0); co.rotation_euler = (math.pi / 2, 0, 0)
scene.render.film_transparent = True
scene.render.filepath = out
bpy.ops.render.render(write_still=True)
