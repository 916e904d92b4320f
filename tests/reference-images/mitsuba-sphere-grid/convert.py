#!/usr/bin/env python3
"""Writes the hand conversions of Mitsuba 3's bsdf_spheres scenes (the mitsuba_*.xml beside
this file) into our JSON: `python3 convert.py` in this folder. PROVENANCE.md says what maps to
what. The spectra of the area light (`400:0, 500:8, 600:15.6, 700:18.4` radiance and a flat
0.78 reflectance over 400-700 nm) are taken to RGB by tools/spectrum-to-rgb.py, which uses the
method of Mitsuba's RGB variants (`tools/spectrum-to-rgb.py "400:0, 500:8, 600:15.6, 700:18.4"`
and, clamped to [0, 1] as Mitsuba clamps reflectances, `--reflectance "400:0.78, ..., 700:0.78"`).
"""
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))
SPHERE = "../mitsuba-infinite-mirrors/sphere.obj"
MUSEUM = "../mitsuba-infinite-mirrors/museum.exr"
LIGHT_RADIANCE = [20.690169, 10.843802, 2.768386]
LIGHT_REFLECTANCE = [0.934827, 0.739887, 0.703983]
LEAF = {"type": "image", "file": "leaf_mask.png"}
# Mitsuba's `constant` emitter of default radiance 1 is a D65 spectrum of unit luminance; its
# RGB variants see it as this colour (the reference's background pixels, exactly).
CONSTANT_RADIANCE = [1.001084089, 0.999707818, 0.999703050]


def rotate(axis, degrees):
    return {"rotate": {"axis": axis, "degrees": degrees}}


def area_light():
    # rectangle.obj faces +z as our quad with u x v = +z does.
    return {"type": "quad", "q": [-1, -1, 0], "u": [2, 0, 0], "v": [0, 2, 0], "material": "light",
            "transform": [rotate([0, 1, 0], 120), {"scale": 2}, {"translate": [-4, 0, 6]}]}


def sphere_grid(description, lights=None, background=None, light=False):
    air = {"ext_ior": "air"}
    m = {
        "diffuse": {"type": "lambertian", "albedo": [0.2, 0.5, 0.3], "one_sided": True},
        "wood": {"type": "lambertian", "albedo": {"type": "image", "file": "wood.jpg"},
                 "one_sided": True},
        "diamond": {"type": "dielectric", "ior": "diamond", **air},
        "plastic": {"type": "plastic", "albedo": [0.1, 0.27, 0.36], "ior": 1.9, **air,
                    "one_sided": True},
        "glass-beckmann": {"type": "dielectric", "ior": "bk7", **air, "alpha": 0.02,
                           "distribution": "beckmann"},
        "glass-ggx": {"type": "dielectric", "ior": "bk7", **air, "alpha": 0.1,
                      "distribution": "ggx"},
        "roughplastic-black": {"type": "plastic", "albedo": 0, "ior": "polypropylene", **air,
                               "alpha": 0.1, "distribution": "beckmann", "one_sided": True},
        "roughplastic-grey": {"type": "plastic", "albedo": 0.5, "ior": "polypropylene", **air,
                              "alpha": 0.05, "distribution": "beckmann", "one_sided": True},
        "conductor": {"type": "conductor", "eta": 0.789, "k": 6.15, "one_sided": True},
        "roughconductor": {"type": "conductor", "eta": 0.789, "k": 6.15, "alpha": 0.05,
                           "distribution": "beckmann", "one_sided": True},
        # mask over twosided over diffuse, and mask over diffuse
        "leaf-twosided": {"type": "lambertian", "albedo": [0.1, 0.8, 0.1], "opacity": LEAF},
        "leaf": {"type": "lambertian", "albedo": [0.1, 0.8, 0.1], "opacity": LEAF,
                 "one_sided": True},
    }
    if light:
        m["light"] = {"type": "diffuse_light", "radiance": LIGHT_RADIANCE,
                      "albedo": LIGHT_REFLECTANCE}

    def sphere(material, at):
        return {"type": "mesh", "file": SPHERE, "material": material,
                "transform": [{"translate": at}]}

    objects = [sphere("diffuse", [0, -6, 0]), sphere("wood", [0, -3, 0]),
               sphere("diamond", [0, 0, 0]), sphere("plastic", [0, 3, 0]),
               sphere("glass-beckmann", [0, 6, 0]), sphere("glass-ggx", [0, 6, 3]),
               sphere("roughplastic-black", [0, 3, 3]), sphere("roughplastic-grey", [0, 0, 3]),
               sphere("conductor", [0, -3, 3]), sphere("roughconductor", [0, -6, 3]),
               {"type": "mesh", "file": "rectangle.obj", "material": "leaf-twosided",
                "transform": [rotate([0, 0, 1], -90), rotate([0, 1, 0], 90),
                              {"translate": [0, -6, -3]}]},
               {"type": "mesh", "file": "rectangle.obj", "material": "leaf",
                "transform": [rotate([0, 0, 1], -90), rotate([0, 1, 0], -90),
                              rotate([1, 0, 0], 180), {"translate": [0, -3, -3]}]}]
    if light:
        objects.append(area_light())
    scene = {"description": description,
             "render": {"width": 48, "height": 48, "spp": 256, "max_depth": 2},
             "camera": {"look_from": [-24, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1],
                        "vfov": 34.0214}}
    if background is not None:
        scene["background"] = background
    if lights:
        scene["lights"] = lights
    scene["materials"] = m
    scene["objects"] = objects
    return scene


def textured_diffuse():
    return {
        "description": "Mitsuba 3's bsdf_spheres/test_textured_diffuse_path.xml (with "
                       "fragments/single_sphere.xml) by hand: a wood-textured diffuse sphere "
                       "under an area light, an environment map and a point light",
        "render": {"width": 48, "height": 48, "spp": 256, "max_depth": 2},
        "camera": {"look_from": [-4, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1],
                   "vfov": 34.0214},
        "background": {"type": "environment", "file": MUSEUM, "rotation": 180,
                       "rows_at_poles": True},
        "lights": [{"type": "point", "position": [-4, 0, -6], "intensity": 300}],
        "materials": {
            "wood": {"type": "lambertian", "albedo": {"type": "image", "file": "wood.jpg"},
                     "one_sided": True},
            "light": {"type": "diffuse_light", "radiance": LIGHT_RADIANCE,
                      "albedo": LIGHT_REFLECTANCE}},
        "objects": [{"type": "mesh", "file": SPHERE, "material": "wood"}, area_light()],
    }


def main():
    grid = "Mitsuba 3's bsdf_spheres regression scene (%s with fragments/sphere_grid.xml) by " \
           "hand: twelve objects of ten material kinds, two of them opacity-masked leaves, %s"
    scenes = {
        "pointlight": sphere_grid(grid % ("test_pointlight_path.xml", "under a point light"),
                                  lights=[{"type": "point", "position": [-4, 0, 6],
                                           "intensity": 300}]),
        "arealight": sphere_grid(grid % ("test_arealight_path.xml", "under an area light"),
                                 light=True),
        "constant": sphere_grid(grid % ("test_constant_path.xml", "under a constant sky"),
                                background={"type": "constant", "radiance": CONSTANT_RADIANCE}),
        "envmap": sphere_grid(grid % ("test_envmap_path.xml", "under an environment map"),
                              background={"type": "environment", "file": MUSEUM,
                                          "rotation": 180, "rows_at_poles": True}),
        "textured_diffuse": textured_diffuse(),
    }
    for name, scene in scenes.items():
        with open(os.path.join(HERE, name + ".json"), "w") as f:
            json.dump(scene, f, indent=1)
            f.write("\n")


main()
