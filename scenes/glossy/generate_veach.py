#!/usr/bin/env python3
"""Writes scenes/veach-mis.xml: Veach's multiple-importance-sampling scene (Veach & Guibas 1995, Fig. 9;
Veach's thesis, Fig. 9.8) in the layout of its well-known renderer ports (four sphere lights of equal
power on the x axis, the camera at (0, 6, 27.5)), framed a little lower and wider so that the front plate
is whole (looking at (0, -2, 2.5), 28 degrees). Each plate is an 8 x 1.5
rectangle whose normal bisects the directions to the camera and to the lights' centre, so that every
plate shows the highlight of every light; Beckmann roughconductor, alpha from sharp to rough.

Usage: scenes/glossy/generate_veach.py > scenes/veach-mis.xml
"""
import math

CAMERA = (0.0, 6.0, 27.5)
LIGHTS_CENTRE = (0.0, 0.0, 0.0)
# (radius, radiance): radiance x radius^2 = 1, equal power.
LIGHTS = [(-3.75, 0.03333, 901.803), (-1.25, 0.1, 100.0), (1.25, 0.3, 11.1111), (3.75, 0.9, 1.23457)]
# Plate centres from the lights towards the camera, sharpest nearest the lights (as in Veach's figure).
PLATES = [((0.0, -2.7, 1.2), 0.005), ((0.0, -3.2, 3.0), 0.02), ((0.0, -3.6, 4.9), 0.07), ((0.0, -3.9, 6.9), 0.25)]
HALF_WIDTH, HALF_DEPTH = 4.0, 0.75


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def norm(a):
    n = math.sqrt(sum(x * x for x in a))
    return tuple(x / n for x in a)


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def plate_matrix(c):
    n = norm(tuple(x + y for x, y in zip(norm(sub(CAMERA, c)), norm(sub(LIGHTS_CENTRE, c)))))
    s = (1.0, 0.0, 0.0)  # the plate's width along x
    t = cross(n, s)  # its depth, in the plane of the camera and the lights
    cols = [tuple(HALF_WIDTH * v for v in s), tuple(HALF_DEPTH * v for v in t), n, c]
    rows = [[cols[j][i] for j in range(4)] for i in range(3)] + [[0.0, 0.0, 0.0, 1.0]]
    return ", ".join(f"{v:.6g}" for row in rows for v in row)


def main():
    out = ['<?xml version="1.0"?>',
           "<!-- Veach's multiple-importance-sampling scene, written by scenes/glossy/generate_veach.py (which",
           "     says how the plates are placed). Four glossy plates (Beckmann roughconductor, alpha 0.005 to",
           "     0.25 from back to front) under four sphere lights of equal power, radius 0.033 to 0.9: light",
           "     sampling fails on the sharp plates and small lights' opposite, BSDF sampling on the rough",
           "     plates, MIS is good everywhere. Direct illumination only. -->",
           "<scene>",
           '\t<integrator type="direct">',
           '\t\t<string name="measure" value="mis"/>',
           '\t\t<string name="lightMeasure" value="solid-angle"/>',
           '\t\t<string name="heuristic" value="power"/>',
           "\t</integrator>",
           "",
           '\t<sampler type="independent">',
           '\t\t<integer name="sampleCount" value="64"/>',
           "\t</sampler>",
           "",
           '\t<camera type="perspective">',
           '\t\t<transform name="toWorld">',
           '\t\t\t<lookat origin="0, 6, 27.5" target="0, -2, 2.5" up="0, 1, 0"/>',
           "\t\t</transform>",
           '\t\t<float name="fov" value="28"/>',
           '\t\t<integer name="width" value="768"/>',
           '\t\t<integer name="height" value="512"/>',
           "\t</camera>",
           ""]
    for x, r, L in LIGHTS:
        out += ['\t<shape type="sphere">',
                f'\t\t<point name="center" value="{x}, 0, 0"/>',
                f'\t\t<float name="radius" value="{r}"/>',
                f'\t\t<emitter type="area">',
                f'\t\t\t<color name="radiance" value="{L}, {L}, {L}"/>',
                "\t\t</emitter>",
                '\t\t<bsdf type="diffuse">',
                '\t\t\t<color name="albedo" value="0"/>',
                "\t\t</bsdf>",
                "\t</shape>"]
    out.append("")
    for c, alpha in PLATES:
        out += ['\t<shape type="rectangle">',
                f'\t\t<string name="name" value="plate alpha {alpha}"/>',
                '\t\t<transform name="toWorld">',
                f'\t\t\t<matrix value="{plate_matrix(c)}"/>',
                "\t\t</transform>",
                '\t\t<bsdf type="roughconductor">',
                '\t\t\t<string name="distribution" value="beckmann"/>',
                f'\t\t\t<float name="alpha" value="{alpha}"/>',
                '\t\t\t<color name="specular_reflectance" value="0.6, 0.8, 1.0"/>',
                "\t\t</bsdf>",
                "\t</shape>"]
    # A dark diffuse floor and back wall behind the plates.
    out += ["",
            '\t<shape type="rectangle">',
            '\t\t<transform name="toWorld">',
            '\t\t\t<scale value="12, 12, 1"/>',
            '\t\t\t<rotate axis="1, 0, 0" angle="-90"/>',
            '\t\t\t<translate value="0, -4.5, 4"/>',
            "\t\t</transform>",
            '\t\t<bsdf type="diffuse">',
            '\t\t\t<color name="albedo" value="0.3, 0.3, 0.3"/>',
            "\t\t</bsdf>",
            "\t</shape>",
            '\t<shape type="rectangle">',
            '\t\t<transform name="toWorld">',
            '\t\t\t<scale value="12, 8, 1"/>',
            '\t\t\t<translate value="0, 3, -3"/>',
            "\t\t</transform>",
            '\t\t<bsdf type="diffuse">',
            '\t\t\t<color name="albedo" value="0.3, 0.3, 0.3"/>',
            "\t\t</bsdf>",
            "\t</shape>",
            "</scene>"]
    print("\n".join(out))


main()
