"""Compares a source BVH take with motifmine's export of it, as Blender's BVH importer sees them.

Run inside Blender (Debian's `blender`, 3.4 here), one line of output per pair:

    blender -b --factory-startup --python scripts/blender_bvh_roundtrip.py -- \
        SOURCE.bvh EXPORT.bvh FIRST_FRAME [SOURCE.bvh EXPORT.bvh FIRST_FRAME ...]

FIRST_FRAME is the source frame that is the export's frame 0 (the clip's `source_first_frame`,
1 when the import dropped a converter's T-pose). Both files are imported with the same options;
for every frame of the export, each joint the two share by name is placed in world space by
Blender's own evaluation, and the largest distance is reported against the body's height (the
source's vertical extent of joints over its first frame). Joints only in the source (a static top
joint the import folded into the root) are listed, not compared. scripts/check_blender_roundtrip.sh
runs this on the three BVH families of ../shared and the studio rig.
"""

import builtins
import json
import sys

import bpy

# Blender 3.4's importer opens files with mode 'rU', which Python 3.11 refuses.
_open = builtins.open


def _open_without_u(file, mode="r", *args, **kwargs):
    return _open(file, mode.replace("U", ""), *args, **kwargs)


builtins.open = _open_without_u


def import_armature(path, frame_start):
    before = set(bpy.data.objects)
    bpy.ops.import_anim.bvh(filepath=path, frame_start=frame_start, global_scale=1.0,
                            rotate_mode="NATIVE", use_fps_scale=False,
                            update_scene_fps=False, update_scene_duration=False)
    (armature,) = [o for o in bpy.data.objects if o not in before and o.type == "ARMATURE"]
    return armature


def frame_count(path):
    with _open(path) as handle:
        for line in handle:
            if line.strip().startswith("Frames:"):
                return int(line.split(":")[1])
    raise SystemExit(f"{path}: no 'Frames:' line")


def heads(armature, names):
    world = armature.matrix_world
    return {name: world @ armature.pose.bones[name].head for name in names}


def compare(source_path, export_path, first_frame):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    source = import_armature(source_path, 1)
    exported = import_armature(export_path, 1 + first_frame)
    source_names = [b.name for b in source.pose.bones]
    export_names = {b.name for b in exported.pose.bones}
    shared = [n for n in source_names if n in export_names]
    scene = bpy.context.scene
    frames = frame_count(export_path)
    scene.frame_set(1 + first_frame)
    start = heads(source, source_names)
    ys = [v.z for v in start.values()]  # Blender is Z-up
    height = max(ys) - min(ys)
    worst, worst_at = 0.0, None
    for k in range(frames):
        scene.frame_set(1 + first_frame + k)
        a, b = heads(source, shared), heads(exported, shared)
        for name in shared:
            d = (a[name] - b[name]).length
            if d > worst:
                worst, worst_at = d, (k, name)
    return {"source": source_path, "export": export_path, "frames": frames,
            "joints_compared": len(shared),
            "joints_only_in_source": [n for n in source_names if n not in export_names],
            "body_height": height, "max_distance": worst,
            "max_relative": worst / height if height > 0 else float("inf"),
            "worst_frame_joint": worst_at}


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if not args or len(args) % 3:
        raise SystemExit("usage: blender -b --python blender_bvh_roundtrip.py -- "
                         "SOURCE EXPORT FIRST_FRAME [...]")
    for i in range(0, len(args), 3):
        print("ROUNDTRIP " + json.dumps(compare(args[i], args[i + 1], int(args[i + 2]))))


main()
