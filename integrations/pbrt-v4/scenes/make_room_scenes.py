#!/usr/bin/python3
"""Writes the three room scenes of integrations/pbrt-v4/scenes (room_sphere_light,
room_rect_light and room_lens_motion): curved and subdivided meshes on a floor
with walls, lit by a small spherical area light or a small rectangular one,
diffuse and glossy materials, and in the third a thin lens and an object moving
while the shutter is open; scenes a renderer's user would set up, written by
this project (every mesh is computed here, no scene file is copied).

  /usr/bin/python3 integrations/pbrt-v4/scenes/make_room_scenes.py

rewrites the three files beside this script (deterministic: the same text each
run); --check only says whether they are its output. Each renders direct lighting as written ("path", depth 1); the
benchmark's "path5" mode renders it with "path" at depth 5.
"""

import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def fmt(values):
    return " ".join(f"{v:.5g}" for v in values)


def torus(R, r, nu, nv):
    """A torus about z of radii R and r: points, normals, triangle indices."""
    P, N, idx = [], [], []
    for i in range(nu):
        u = 2 * math.pi * i / nu
        for j in range(nv):
            v = 2 * math.pi * j / nv
            n = (math.cos(u) * math.cos(v), math.sin(u) * math.cos(v), math.sin(v))
            c = (R * math.cos(u), R * math.sin(u), 0.0)
            P += [c[0] + r * n[0], c[1] + r * n[1], c[2] + r * n[2]]
            N += list(n)
    for i in range(nu):
        for j in range(nv):
            a, b = i * nv + j, ((i + 1) % nu) * nv + j
            c, d = i * nv + (j + 1) % nv, ((i + 1) % nu) * nv + (j + 1) % nv
            idx += [a, b, d, a, d, c]
    return P, N, idx


def mesh(P, N, idx, indent="  "):
    return (f'{indent}Shape "trianglemesh"\n{indent}  "point3 P" [ {fmt(P)} ]\n'
            f'{indent}  "normal N" [ {fmt(N)} ]\n{indent}  "integer indices" [ {" ".join(map(str, idx))} ]\n')


# A cube's corners and faces as triangles: Loop subdivision rounds it.
CUBE_P = [-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1, -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1]
CUBE_I = [0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
          1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7]
# The cube as a pbrt shape, three levels of Loop subdivision.
LOOP_CUBE = (f'  Shape "loopsubdiv" "integer levels" [ 3 ] "point3 P" [ {fmt(CUBE_P)} ]\n'
             f'    "integer indices" [ {" ".join(map(str, CUBE_I))} ]\n')
# An octahedron, subdivided: a smooth blob.
OCTA_P = [1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1]
OCTA_I = [0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5]


def room(floor_rgb, wall_rgb):
    """A floor (z = 0) and two walls (y = 2.2 behind, x = -2.2 to the left)."""
    return f"""# The room: a floor, a back wall and a left wall.
AttributeBegin
  Material "diffuse" "rgb reflectance" [ {fmt(floor_rgb)} ]
  Shape "bilinearmesh" "point3 P" [ -2.2 -3 0   4 -3 0   -2.2 2.2 0   4 2.2 0 ]
AttributeEnd
AttributeBegin
  Material "diffuse" "rgb reflectance" [ {fmt(wall_rgb)} ]
  Shape "bilinearmesh" "point3 P" [ -2.2 2.2 0   4 2.2 0   -2.2 2.2 3   4 2.2 3 ]
  Shape "bilinearmesh" "point3 P" [ -2.2 -3 0   -2.2 2.2 0   -2.2 -3 3   -2.2 2.2 3 ]
AttributeEnd
"""


def sphere_light(what, position, rgb, radius):
    """A small spherical area light (black, so only its emission is seen)."""
    return f"""# The light: {what}.
AttributeBegin
  Translate {position}
  AreaLightSource "diffuse" "rgb L" [ {rgb} ]
  Material "diffuse" "rgb reflectance" [ 0 0 0 ]
  Shape "sphere" "float radius" [ {radius:g} ]
AttributeEnd

"""


def header(name, comment, lookat, lens=""):
    return (comment + f"""LookAt {lookat}
Camera "perspective" "float fov" [ 42 ]{" " + lens if lens else ""}
Film "rgb" "integer xresolution" [ 192 ] "integer yresolution" [ 192 ] "string filename" [ "{name}.exr" ]
Integrator "path" "integer maxdepth" [ 1 ]
WorldBegin

""")


def sphere_light_scene():
    P, N, idx = torus(0.42, 0.14, 40, 20)
    comment = """# A room lit by a small spherical light (alignset integrations/pbrt-v4;
# written by make_room_scenes.py): a glossy torus, a subdivided rounded cube,
# a subdivided blob and a diffuse cylinder on a floor with two walls; their
# soft shadows fall on the floor and the walls, and the silhouettes and
# glossy highlights are film edges. Direct lighting as written.
#   pbrt room_sphere_light.pbrt       (pbrt's defaults: zsobol, Gaussian filter)
"""
    s = header("room_sphere_light", comment, "1.6 -3.6 2.2   0.2 0.4 0.45   0 0 1")
    s += sphere_light("a sphere of radius 0.09 above the objects", "0.6 -0.2 2.1", "160 150 130", 0.09)
    s += room([0.55, 0.55, 0.52], [0.6, 0.58, 0.55])
    s += f"""
# A glossy torus, tilted.
AttributeBegin
  Translate -0.3 0.2 0.32  Rotate 28 1 0.3 0
  Material "coateddiffuse" "rgb reflectance" [ 0.6 0.15 0.1 ] "float roughness" [ 0.05 ]
{mesh(P, N, idx)}AttributeEnd

# A rounded cube (Loop subdivision of a cube).
AttributeBegin
  Translate 0.95 0.75 0.38  Rotate 35 0 0 1  Scale 0.42 0.42 0.42
  Material "coateddiffuse" "rgb reflectance" [ 0.15 0.3 0.6 ] "float roughness" [ 0.15 ]
{LOOP_CUBE}AttributeEnd

# A subdivided blob, squashed.
AttributeBegin
  Translate 0.25 -0.9 0.22  Scale 0.3 0.24 0.22
  Material "diffuse" "rgb reflectance" [ 0.7 0.65 0.3 ]
  Shape "loopsubdiv" "integer levels" [ 3 ] "point3 P" [ {fmt(OCTA_P)} ]
    "integer indices" [ {" ".join(map(str, OCTA_I))} ]
AttributeEnd

# A diffuse cylinder, standing.
AttributeBegin
  Translate -1.2 1.1 0
  Material "diffuse" "rgb reflectance" [ 0.4 0.55 0.35 ]
  Shape "cylinder" "float radius" [ 0.22 ] "float zmin" [ 0 ] "float zmax" [ 1.1 ]
  Translate 0 0 1.1
  Shape "disk" "float radius" [ 0.22 ]
AttributeEnd
"""
    return s


def rect_light_scene():
    P, N, idx = torus(0.3, 0.1, 36, 18)
    comment = """# A room lit by a small rectangular light (alignset integrations/pbrt-v4;
# written by make_room_scenes.py): a subdivided rounded cube, a glossy sphere,
# a torus standing on its rim and a thin diffuse slab, on a floor with two
# walls; the rectangle's two edge directions make penumbrae of two slopes.
# Direct lighting as written.
#   pbrt room_rect_light.pbrt         (pbrt's defaults: zsobol, Gaussian filter)
"""
    s = header("room_rect_light", comment, "-0.4 -3.8 1.9   0.3 0.5 0.5   0 0 1")
    s += """# The light: a 0.4 x 0.12 rectangle at z = 2.4, tilted towards the back wall.
AttributeBegin
  Translate 0.5 -0.4 2.4  Rotate 20 1 0 0  Rotate 30 0 0 1
  AreaLightSource "diffuse" "rgb L" [ 90 95 100 ] "bool twosided" [ true ]
  Shape "bilinearmesh" "point3 P" [ -0.2 -0.06 0   0.2 -0.06 0   -0.2 0.06 0   0.2 0.06 0 ]
AttributeEnd

"""
    s += room([0.5, 0.5, 0.5], [0.62, 0.6, 0.56])
    s += f"""
# A rounded cube.
AttributeBegin
  Translate -0.7 0.5 0.35  Rotate -20 0 0 1  Scale 0.38 0.38 0.38
  Material "diffuse" "rgb reflectance" [ 0.7 0.35 0.2 ]
{LOOP_CUBE}AttributeEnd

# A glossy sphere.
AttributeBegin
  Translate 0.55 0.35 0.36
  Material "coateddiffuse" "rgb reflectance" [ 0.2 0.45 0.3 ] "float roughness" [ 0.08 ]
  Shape "sphere" "float radius" [ 0.36 ]
AttributeEnd

# A torus standing on its rim.
AttributeBegin
  Translate 1.35 -0.45 0.4  Rotate 90 1 0 0  Rotate 20 0 1 0
  Material "conductor" "spectrum eta" "metal-Cu-eta" "spectrum k" "metal-Cu-k" "float roughness" [ 0.2 ]
{mesh(P, N, idx)}AttributeEnd

# A thin slab on two posts (a shadow whose edges are long and straight).
AttributeBegin
  Translate -0.2 -0.9 0.55  Rotate 12 0 0 1
  Material "diffuse" "rgb reflectance" [ 0.35 0.35 0.4 ]
  Shape "bilinearmesh" "point3 P" [ -0.45 -0.2 0   0.45 -0.2 0   -0.45 0.2 0   0.45 0.2 0 ]
  Translate -0.4 0 0
  Shape "cylinder" "float radius" [ 0.03 ] "float zmin" [ -0.55 ] "float zmax" [ 0 ]
  Translate 0.8 0 0
  Shape "cylinder" "float radius" [ 0.03 ] "float zmin" [ -0.55 ] "float zmax" [ 0 ]
AttributeEnd
"""
    return s


def lens_motion_scene():
    P, N, idx = torus(0.34, 0.11, 36, 18)
    comment = """# A room seen through a thin lens, with an object moving while the shutter is
# open (alignset integrations/pbrt-v4; written by make_room_scenes.py): a glossy
# sphere in the foreground out of focus, a torus in focus, a rounded cube
# sliding sideways and a diffuse post, lit by a small spherical light. The
# defocused silhouettes are edges in the film and lens samples together, the
# moving cube's edges and its shadow's in the film, time and light samples:
# the camera's time and lens dimensions are live. Direct lighting as written.
#   pbrt room_lens_motion.pbrt        (pbrt's defaults: zsobol, Gaussian filter)
"""
    s = header("room_lens_motion", comment, "1.2 -3.9 1.6   0 0.3 0.5   0 0 1",
               '"float lensradius" [ 0.06 ] "float focaldistance" [ 4.55 ]')
    s += sphere_light("a sphere of radius 0.1 above and in front of the objects", "-0.3 -0.6 2.2",
                      "320 320 340", 0.1)
    s += room([0.52, 0.5, 0.48], [0.58, 0.6, 0.62])
    s += f"""
# A glossy sphere close to the lens, out of focus.
AttributeBegin
  Translate 0.75 -2.0 0.28
  Material "coateddiffuse" "rgb reflectance" [ 0.55 0.5 0.15 ] "float roughness" [ 0.06 ]
  Shape "sphere" "float radius" [ 0.28 ]
AttributeEnd

# A torus lying on the floor, in focus.
AttributeBegin
  Translate 0.1 0.3 0.11
  Material "coateddiffuse" "rgb reflectance" [ 0.5 0.12 0.15 ] "float roughness" [ 0.1 ]
{mesh(P, N, idx)}AttributeEnd

# A rounded cube sliding 0.4 along x while the shutter is open.
AttributeBegin
  ActiveTransform EndTime
  Translate 0.4 0 0
  ActiveTransform All
  Translate -1.1 0.9 0.36  Rotate 25 0 0 1  Scale 0.36 0.36 0.36
  Material "diffuse" "rgb reflectance" [ 0.2 0.35 0.65 ]
{LOOP_CUBE}AttributeEnd

# A diffuse post behind the torus.
AttributeBegin
  Translate 1.2 1.2 0
  Material "diffuse" "rgb reflectance" [ 0.6 0.6 0.55 ]
  Shape "cylinder" "float radius" [ 0.06 ] "float zmin" [ 0 ] "float zmax" [ 1.5 ]
AttributeEnd
"""
    return s


def main():
    scenes = (("room_sphere_light", sphere_light_scene()), ("room_rect_light", rect_light_scene()),
              ("room_lens_motion", lens_motion_scene()))
    if sys.argv[1:] == ["--check"]:
        # The committed files are this script's output (a CTest).
        stale = [name for name, text in scenes if open(os.path.join(HERE, name + ".pbrt")).read() != text]
        for name in stale:
            print(f"{name}.pbrt differs from make_room_scenes.py's output: run it and commit both")
        return 1 if stale else 0
    for name, text in scenes:
        with open(os.path.join(HERE, name + ".pbrt"), "w") as f:
            f.write(text)
        print(f"wrote {name}.pbrt")
    return 0


if __name__ == "__main__":
    sys.exit(main())
