import sys, numpy
numpy.bool = bool
import bpy
argv = sys.argv[sys.argv.index("--") + 1:]
src, dst = argv
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=src)
bpy.ops.export_scene.gltf(filepath=dst, export_format='GLTF_SEPARATE', export_tangents=True, export_cameras=True)
