"""Scenes of bench/update_bake.sh, written into a work directory.

  update_scenes.py WORK_DIR MODELS_DIR

bunny_spot_{a,b}.json: the bunny and spot side by side on a ground grid,
with a small cube that moves between a and b (a hilbert layout's scene).
wall_cubes_{a,b}.json: cubes-wall-like geometry (ground, back wall, 3x3
cubes of 0.4 as separate meshes, the built-in's camera), one corner cube
moved by 0.25 between a and b (a camera layout's scene).
"""
import json
import os
import sys

work, models = sys.argv[1], sys.argv[2]


def grid(path, n, corner, du, dv, normal):
    """n x n vertices corner + i*du/(n-1) + j*dv/(n-1), triangles facing normal."""
    with open(path, "w") as f:
        for j in range(n):
            for i in range(n):
                p = [corner[k] + du[k] * i / (n - 1) + dv[k] * j / (n - 1) for k in range(3)]
                f.write("v %.6f %.6f %.6f\n" % tuple(p))
        f.write("vn %g %g %g\n" % tuple(normal))
        for j in range(n - 1):
            for i in range(n - 1):
                a = j * n + i + 1
                b, c = a + 1, a + n
                d = c + 1
                f.write("f %d//1 %d//1 %d//1\nf %d//1 %d//1 %d//1\n" % (a, c, b, b, c, d))


def cube(path):
    """Unit cube [-0.5, 0.5]^3 with flat faces (4 vertices each), 3x3 quads per face."""
    faces = [((1, 0, 0), (0, 0, -1), (0, 1, 0)), ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
             ((0, 1, 0), (1, 0, 0), (0, 0, -1)), ((0, -1, 0), (1, 0, 0), (0, 0, 1)),
             ((0, 0, 1), (1, 0, 0), (0, 1, 0)), ((0, 0, -1), (-1, 0, 0), (0, 1, 0))]
    n = 4
    with open(path, "w") as f:
        base = 1
        for fi, (nrm, u, v) in enumerate(faces):
            f.write("vn %d %d %d\n" % nrm)
            for j in range(n):
                for i in range(n):
                    s, t = i / (n - 1) - 0.5, j / (n - 1) - 0.5
                    p = [0.5 * nrm[k] + s * u[k] + t * v[k] for k in range(3)]
                    f.write("v %.6f %.6f %.6f\n" % tuple(p))
            for j in range(n - 1):
                for i in range(n - 1):
                    a = base + j * n + i
                    b, c = a + 1, a + n
                    d = c + 1
                    k = fi + 1
                    f.write("f %d//%d %d//%d %d//%d\nf %d//%d %d//%d %d//%d\n" %
                            (a, k, b, k, d, k, a, k, d, k, c, k))
            base += n * n


def link(name):
    dst = os.path.join(work, name)
    if not os.path.exists(dst):
        os.symlink(os.path.join(models, name), dst)


def mesh(file, scale=None, translate=None, rotate=None):
    m = {"file": file}
    t = {}
    if scale is not None:
        t["scale"] = scale
    if rotate is not None:
        t["rotate_y_degrees"] = rotate
    if translate is not None:
        t["translate"] = translate
    if t:
        m["transform"] = t
    return m


def write(name, meshes, camera=None):
    scene = {"meshes": meshes}
    if camera:
        scene["camera"] = camera
    with open(os.path.join(work, name), "w") as f:
        json.dump(scene, f, indent=1)


os.makedirs(work, exist_ok=True)
link("bunny.obj")
link("spot.obj")
cube(os.path.join(work, "cube.obj"))
grid(os.path.join(work, "ground48.obj"), 48, (-2, -0.74, 2), (4, 0, 0), (0, 0, -4), (0, 1, 0))
for name, cube_at in (("a", [-1.3, -0.665, 1.2]), ("b", [-1.0, -0.665, 1.45])):
    write("bunny_spot_%s.json" % name, [
        mesh("ground48.obj"),
        mesh("spot.obj", rotate=30),
        mesh("bunny.obj", scale=5, translate=[1.1, -0.9, 0.2]),
        mesh("cube.obj", scale=0.15, translate=cube_at),
    ])

grid(os.path.join(work, "ground64.obj"), 64, (-2, 0, 2), (4, 0, 0), (0, 0, -4), (0, 1, 0))
grid(os.path.join(work, "wall.obj"), 33, (-2, 0, -2), (4, 0, 0), (0, 2, 0), (0, 0, 1))
camera = {"eye": [0, 2.6, 4.2], "target": [0, 0.5, -0.4]}
for name, shift in (("a", 0.0), ("b", 0.25)):
    meshes = [mesh("ground64.obj"), mesh("wall.obj")]
    for a in (-1, 0, 1):
        for b in (-1, 0, 1):
            x, z = 0.8 * a, 0.8 * b
            if (a, b) == (1, 1):
                x += shift
            meshes.append(mesh("cube.obj", scale=0.4, translate=[x, 0.2, z]))
    write("wall_cubes_%s.json" % name, meshes, camera)
