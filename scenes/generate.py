#!/usr/bin/env python3
"""Writes the shipped scene files. The JSON files are committed; this script documents how
they were made (the Cornell walls shared by five scenes, the random floor and sphere cluster
of `everything`) and remakes them: `python3 scenes/generate.py`.

The scenes follow Peter Shirley's "Ray Tracing in One Weekend" series (the seed):
The Next Week (RTNW) §7-10 and The Rest of Your Life (ROYL) §6-12."""
import json
import math
import os
import random
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def cornell_camera():
    return {"look_from": [278, 278, -800], "look_at": [278, 278, 0], "up": [0, 1, 0], "vfov": 40}


def cornell_materials(light=15):
    return {
        "red": {"type": "lambertian", "albedo": [0.65, 0.05, 0.05]},
        "white": {"type": "lambertian", "albedo": [0.73, 0.73, 0.73]},
        "green": {"type": "lambertian", "albedo": [0.12, 0.45, 0.15]},
        "light": {"type": "diffuse_light", "radiance": [light, light, light]},
    }


def cornell_walls(light_quad=None):
    # ROYL §6: walls face into the box; the light faces down.
    light = light_quad or {"q": [213, 554, 227], "u": [130, 0, 0], "v": [0, 0, 105]}
    return [
        {"type": "quad", "q": [555, 0, 0], "u": [0, 0, 555], "v": [0, 555, 0], "material": "green"},
        {"type": "quad", "q": [0, 0, 555], "u": [0, 0, -555], "v": [0, 555, 0], "material": "red"},
        dict(type="quad", material="light", **light),
        {"type": "quad", "q": [0, 555, 0], "u": [555, 0, 0], "v": [0, 0, 555], "material": "white"},
        {"type": "quad", "q": [0, 0, 555], "u": [555, 0, 0], "v": [0, 0, -555], "material": "white"},
        {"type": "quad", "q": [555, 0, 555], "u": [-555, 0, 0], "v": [0, 555, 0], "material": "white"},
    ]


def rotate_y(degrees):
    return {"rotate": {"axis": [0, 1, 0], "degrees": degrees}}


def tall_box(lift=0, **kw):
    return dict(type="box", min=[0, 0, 0], max=[165, 330, 165],
                transform=[rotate_y(15), {"translate": [265, lift, 295]}], **kw)


def short_box(lift=0, **kw):
    return dict(type="box", min=[0, 0, 0], max=[165, 165, 165],
                transform=[rotate_y(-18), {"translate": [130, lift, 65]}], **kw)




def cornell_scene(description, objects, materials=None, media=None, light_quad=None, light=15,
                  spp=64):
    scene = {
        "description": description,
        "render": {"width": 600, "height": 600, "spp": spp, "max_depth": 50},
        "camera": cornell_camera(),
        "background": [0, 0, 0],
        "materials": {**cornell_materials(light), **(materials or {})},
    }
    if media:
        scene["media"] = media
    scene["objects"] = cornell_walls(light_quad) + objects
    return scene


def everything():
    # RTNW §10 final scene. The book's moving sphere is static here (no motion blur).
    rng = random.Random(1)
    objects = []
    w = 100.0
    floor = []
    for i in range(20):
        for j in range(20):
            x0, z0 = -1000.0 + i * w, -1000.0 + j * w
            y1 = round(rng.uniform(1, 101), 3)
            floor.append({"type": "box", "min": [x0, 0, z0], "max": [x0 + w, y1, z0 + w],
                          "material": "ground"})
    objects.append({"type": "group", "objects": floor})
    objects.append({"type": "quad", "q": [123, 554, 147], "u": [300, 0, 0], "v": [0, 0, 265],
                    "material": "light"})
    objects.append({"type": "sphere", "center": [400, 400, 200], "radius": 50, "material": "orange"})
    objects.append({"type": "sphere", "center": [260, 150, 45], "radius": 50, "material": "glass"})
    objects.append({"type": "sphere", "center": [0, 150, 145], "radius": 50, "material": "brushed"})
    # A glass ball filled with blue smoke, and thin fog over the whole scene.
    objects.append({"type": "sphere", "center": [360, 150, 145], "radius": 70, "material": "glass",
                    "interior": "blue_smoke"})
    objects.append({"type": "sphere", "center": [0, 0, 0], "radius": 5000, "interior": "fog"})
    objects.append({"type": "sphere", "center": [400, 200, 400], "radius": 100, "material": "earth"})
    objects.append({"type": "sphere", "center": [220, 280, 300], "radius": 80, "material": "marble"})
    cluster = []
    for _ in range(1000):
        c = [round(rng.uniform(0, 165), 3) for _ in range(3)]
        cluster.append({"type": "sphere", "center": c, "radius": 10, "material": "white"})
    objects.append({"type": "group", "objects": cluster,
                    "transform": [rotate_y(15), {"translate": [-100, 270, 395]}]})
    return {
        "description": "The final scene of Ray Tracing: The Next Week (section 10)",
        "render": {"width": 800, "height": 800, "spp": 256, "max_depth": 40},
        "camera": {"look_from": [478, 278, -600], "look_at": [278, 278, 0], "up": [0, 1, 0],
                   "vfov": 40},
        "background": [0, 0, 0],
        "materials": {
            "ground": {"type": "lambertian", "albedo": [0.48, 0.83, 0.53]},
            "light": {"type": "diffuse_light", "radiance": [7, 7, 7]},
            "orange": {"type": "lambertian", "albedo": [0.7, 0.3, 0.1]},
            "glass": {"type": "dielectric", "ior": 1.5},
            "brushed": {"type": "metal", "albedo": [0.8, 0.8, 0.9], "roughness": 1.0},
            "earth": {"type": "lambertian",
                      "albedo": {"type": "image", "file": "textures/earthmap.jpg"}},
            "marble": {"type": "lambertian", "albedo": {"type": "noise", "scale": 0.2}},
            "white": {"type": "lambertian", "albedo": [0.73, 0.73, 0.73]},
        },
        "media": {
            "blue_smoke": {"density": 0.2, "albedo": [0.2, 0.4, 0.9]},
            "fog": {"density": 0.0001, "albedo": [1, 1, 1]},
        },
        "objects": objects,
    }


def materials():
    """A grid of the material kinds side by side: named metals from smooth to rough, GGX and
    Beckmann, in the back row; glass smooth and rough, a normal-mapped Lambertian and a rough
    metal in the middle; plastics (one bump-mapped), alpha masks and a thin pane in front; glTF's
    metallic-roughness material nearest the camera; on a grey floor under the environment map,
    a small quad light, a point, a spot and
    a directional light. Both engines, every kind and the delta lights."""
    back = [("Au", 0.0, "ggx"), ("Au", 0.1, "ggx"), ("Cu", 0.2, "beckmann"),
            ("Ag", 0.3, "ggx"), ("Al", 0.05, "beckmann"), ("Cr", 0.5, "ggx")]
    materials = {"floor": {"type": "lambertian", "albedo": 0.4},
                 "lamp": {"type": "diffuse_light", "radiance": 12},
                 "glass": {"type": "dielectric", "ior": "bk7"},
                 "glass-ggx-0.05": {"type": "dielectric", "ior": "bk7", "alpha": 0.05},
                 "glass-beckmann-0.3": {"type": "dielectric", "ior": 1.5, "alpha": 0.3,
                                        "distribution": "beckmann"},
                 "water-ggx-0.15": {"type": "dielectric", "ior": "water", "alpha": 0.15},
                 "white": {"type": "lambertian", "albedo": 0.7,
                           "normal_map": {"type": "image", "file": "textures/dimples_normal.png",
                                          "raw": True, "uv_transform": {"scale": [8, 4]}}},
                 "steel": {"type": "metal", "albedo": [0.8, 0.8, 0.85], "roughness": 0.3}}
    objects = [{"type": "quad", "q": [-10, 0, 10], "u": [20, 0, 0], "v": [0, 0, -20],
                "material": "floor"},
               {"type": "quad", "q": [-1.5, 6, -1.5], "u": [3, 0, 0], "v": [0, 0, 3],
                "material": "lamp"}]
    for i, (metal, alpha, distribution) in enumerate(back):
        name = "%s-%s-%g" % (metal, distribution, alpha)
        materials[name] = {"type": "conductor", "metal": metal, "alpha": alpha,
                           "distribution": distribution}
        objects.append({"type": "sphere", "center": [-5 + 2 * i, 0.9, -1.2], "radius": 0.9,
                        "material": name})
    front = ["glass", "glass-ggx-0.05", "glass-beckmann-0.3", "water-ggx-0.15", "white", "steel"]
    for i, name in enumerate(front):
        objects.append({"type": "sphere", "center": [-5 + 2 * i, 0.7, 1.2], "radius": 0.7,
                        "material": name})
    # Plastics and alpha masks in front: smooth and rough plastic (Mitsuba 3's models), a rough
    # nonlinear one with a texture, a sphere cut by a uv checkerboard, and a leaf cut from a
    # quad and from a mesh rectangle by the same mask; a thin dielectric pane.
    leaf = {"type": "image", "file": "textures/leaf_mask.png"}
    materials.update({
        "plastic": {"type": "plastic", "albedo": [0.1, 0.27, 0.36], "ior": 1.9},
        "plastic-beckmann-0.1": {"type": "plastic", "albedo": 0.5, "alpha": 0.1,
                                 "distribution": "beckmann"},
        "plastic-ggx-0.3-earth": {"type": "plastic", "alpha": 0.3, "nonlinear": True,
                                  "albedo": {"type": "image", "file": "textures/earthmap.jpg"},
                                  "bump_map": {"type": "image", "file": "textures/earthmap.jpg"},
                                  "bump_scale": 0.002},
        "cut-sphere": {"type": "lambertian", "albedo": [0.8, 0.5, 0.2],
                       "opacity": {"type": "uv_checker", "scale": 0.125, "even": 1, "odd": 0}},
        "leaf": {"type": "lambertian", "albedo": [0.1, 0.8, 0.1], "opacity": leaf},
        "pane": {"type": "thin_dielectric", "ior": "bk7"},
    })
    for i, name in enumerate(["plastic", "plastic-beckmann-0.1", "plastic-ggx-0.3-earth",
                              "cut-sphere"]):
        objects.append({"type": "sphere", "center": [-5 + 2 * i, 0.5, 3.2], "radius": 0.5,
                        "material": name})
    objects.append({"type": "quad", "q": [2.2, 0.05, 2.6], "u": [1.2, 0, 0], "v": [0, 1.2, 0],
                    "material": "leaf"})
    # A thin glass pane in front of the first two plastics.
    objects.append({"type": "quad", "q": [-5.6, 0, 4.1], "u": [3.2, 0, 0], "v": [0, 1.1, 0],
                    "material": "pane"})
    objects.append({"type": "mesh", "file": "meshes/rectangle.obj", "material": "leaf",
                    "transform": [{"scale": 0.6}, {"translate": [4.4, 0.65, 3.2]}]})
    # glTF's metallic-roughness material in a row nearest the camera: clearcoated car paint, a
    # rough gold-coloured metal, frosted thin-walled transmission, a textured metallic-roughness
    # map, an emissive surface and a smooth dielectric (a delta lobe over a diffuse base).
    materials.update({
        "gltf-car-paint": {"type": "metallic_roughness", "base_color": [0.6, 0.05, 0.05],
                           "metallic": 0, "roughness": 0.4, "clearcoat": 1,
                           "clearcoat_roughness": 0.05},
        "gltf-gold": {"type": "metallic_roughness", "base_color": [1.0, 0.78, 0.34],
                      "metallic": 1, "roughness": 0.25},
        "gltf-frosted": {"type": "metallic_roughness", "base_color": [0.9, 0.95, 1.0],
                         "metallic": 0, "roughness": 0.3, "transmission": 1},
        "gltf-textured": {"type": "metallic_roughness",
                          "base_color": {"type": "image", "file": "textures/earthmap.jpg"},
                          "metallic_roughness": {"type": "uv_checker", "scale": 0.125,
                                                 "even": [0, 0.2, 1], "odd": [0, 0.8, 0]}},
        "gltf-emissive": {"type": "metallic_roughness", "base_color": 0.2, "metallic": 0,
                          "roughness": 0.5, "emission": [3, 1.5, 0.5]},
        "gltf-smooth": {"type": "metallic_roughness", "base_color": [0.2, 0.4, 0.8],
                        "metallic": 0, "roughness": 0},
    })
    for i, name in enumerate(["gltf-car-paint", "gltf-gold", "gltf-frosted", "gltf-textured",
                              "gltf-emissive", "gltf-smooth"]):
        objects.append({"type": "sphere", "center": [-3.25 + 1.3 * i, 0.35, 5.0], "radius": 0.35,
                        "material": name})
    return {
        "description": "Material kinds side by side: six named metals (Au, Cu, Ag, Al, Cr) from "
                       "smooth to rough, GGX and Beckmann; smooth and rough glass, water, "
                       "normal-mapped Lambertian, rough metal; smooth, rough and textured, "
                       "bump-mapped plastic behind a "
                       "thin glass pane; alpha masks on a sphere, a quad and a mesh; glTF's "
                       "metallic-roughness material (clearcoat, metal, transmission, textured, "
                       "emissive, smooth); under an environment map, a quad "
                       "light, a point, a spot and a directional light",
        "render": {"width": 640, "height": 320, "spp": 64, "max_depth": 32},
        "camera": {"look_from": [0, 4, 13], "look_at": [0, 0.7, 0], "vfov": 28},
        "background": {"type": "environment", "file": "textures/tungsten_envmap.hdr",
                       "rotation": 90, "scale": 0.5},
        "lights": [{"type": "point", "position": [4, 5, 4], "intensity": 25},
                   {"type": "spot", "position": [-4, 6, 3], "look_at": [-3, 0.9, 0],
                    "intensity": 60, "cutoff": 18, "falloff_start": 12},
                   {"type": "directional", "direction": [0.3, -1, -0.4], "irradiance": 0.4}],
        "materials": materials,
        "objects": objects,
    }


def veach_mis():
    """Veach's multiple-importance-sampling scene (thesis, 1997, fig. 9.2): four glossy plates of
    increasing smoothness, each reflecting four spherical lights of increasing size and equal
    power (radiance proportional to 1 / radius^2). Each plate's normal bisects the directions
    to the camera and to the row of lights, so every plate shows all four highlights."""
    import math

    def norm(v):
        length = math.sqrt(sum(c * c for c in v))
        return [c / length for c in v]

    camera = [0.0, 2.0, 15.0]
    light_row = [0.0, 0.0, 0.0]
    objects = []
    materials = {"floor": {"type": "lambertian", "albedo": [0.25, 0.25, 0.25]}}
    roughness = [0.35, 0.2, 0.1, 0.05]  # top (nearest the lights) to bottom
    centers = [[0.0, -2.6, 0.9], [0.0, -3.2, 2.1], [0.0, -3.65, 3.3], [0.0, -3.95, 4.5]]
    for k, (c, r) in enumerate(zip(centers, roughness)):
        to_cam = norm([camera[i] - c[i] for i in range(3)])
        to_light = norm([light_row[i] - c[i] for i in range(3)])
        n = norm([to_cam[i] + to_light[i] for i in range(3)])
        t = norm([0.0, n[2], -n[1]])  # n x (1, 0, 0): u x v then points along n
        q = [c[i] - 4.0 * (1 if i == 0 else 0) - 0.55 * t[i] for i in range(3)]
        name = "plate%d" % (k + 1)
        materials[name] = {"type": "metal", "albedo": [0.8, 0.8, 0.8], "roughness": r}
        objects.append({"type": "quad", "q": [round(x, 5) for x in q], "u": [8, 0, 0],
                        "v": [round(1.1 * x, 5) for x in t], "material": name})
    radii = [0.0333, 0.1, 0.3, 0.9]
    for k, r in enumerate(radii):
        name = "light%d" % (k + 1)
        le = round(1.0 / (r * r), 4)  # equal power: radiance x area is the same for all four
        materials[name] = {"type": "diffuse_light", "radiance": [le, le, le]}
        objects.append({"type": "sphere", "center": [-3.75 + 2.5 * k, 0.0, 0.0], "radius": r,
                        "material": name})
    objects.append({"type": "quad", "q": [-10, -4.2, -4], "u": [0, 0, 14], "v": [20, 0, 0],
                    "material": "floor"})
    objects.append({"type": "quad", "q": [-10, -4.2, -4], "u": [20, 0, 0], "v": [0, 10, 0],
                    "material": "floor"})
    return {
        "description": "Veach's MIS scene: four glossy plates, four sphere lights of equal power",
        "render": {"width": 512, "height": 384, "spp": 64, "max_depth": 8},
        "camera": {"look_from": camera, "look_at": [0, -2, 2.5], "up": [0, 1, 0], "vfov": 28},
        "background": [0, 0, 0],
        "materials": materials,
        "objects": objects,
    }


SCENES = {
    "cornell": cornell_scene(
        "The Cornell box with two white blocks (ROYL section 6)",
        [tall_box(material="white"), short_box(material="white")]),
    "cornell-glass": cornell_scene(
        "The Cornell box with a tall white block and a glass ball (ROYL section 12)",
        [tall_box(material="white"),
         {"type": "sphere", "center": [190, 90, 190], "radius": 90, "material": "glass"}],
        materials={"glass": {"type": "dielectric", "ior": 1.5}}),
    "cornell-mirror": cornell_scene(
        "The Cornell box with a mirror block (ROYL section 12's aluminium block as a perfect mirror)",
        [tall_box(material="mirror"), short_box(material="white")],
        materials={"mirror": {"type": "mirror", "albedo": [0.8, 0.85, 0.88]}}),
    "cornell-smoke": cornell_scene(
        "The Cornell box with the blocks as black smoke and white fog (RTNW section 9)",
        [tall_box(interior="smoke"), short_box(interior="fog")],  # standing on the floor, as in the book
        media={"smoke": {"density": 0.01, "albedo": [0, 0, 0]},
               "fog": {"density": 0.01, "albedo": [1, 1, 1]}},
        light_quad={"q": [113, 554, 127], "u": [330, 0, 0], "v": [0, 0, 305]}, light=7),
    "bunny": cornell_scene(
        "The Stanford bunny (69,451 triangles) in the Cornell box",
        [tall_box(material="white"),
         {"type": "mesh", "file": "meshes/bunny.ply", "material": "white", "normals": "smooth",
          "transform": [{"scale": 1500}, rotate_y(180), {"translate": [200, -49.48, 200]}]}]),
    "dragon": cornell_scene(
        "The Stanford dragon (100,000 triangles) in the Cornell box",
        [{"type": "mesh", "file": "meshes/dragon_100k.obj", "material": "gold", "normals": "smooth",
          "transform": [{"scale": 32}, rotate_y(200), {"translate": [278, 0, 290]}]}],
        materials={"gold": {"type": "metal", "albedo": [0.95, 0.7, 0.3], "roughness": 0.3}}),
    "everything": everything(),
    "veach-mis": veach_mis(),
    # McGuire's OBJ+MTL Cornell box as it is, set up as ../shared's Tungsten reference render
    # (cornell-box/reference-tungsten/README.md): camera, fov, 512 x 512.
    "cornell-mcguire": {
        "description": "Morgan McGuire's Cornell box (OBJ + MTL, materials from the file), "
                       "framed as the Tungsten reference render",
        "render": {"width": 512, "height": 512, "spp": 64, "max_depth": 256},
        "camera": {"look_from": [0, 1, 6.8], "look_at": [0, 1, 0], "up": [0, 1, 0], "vfov": 19.5},
        "background": [0, 0, 0],
        "objects": [{"type": "mesh", "file": "meshes/cornell-mcguire/CornellBox-Original.obj",
                     "materials": "file", "normals": "flat"}],
    },
    # The dragon alone under Tungsten's environment map, set up as ../shared's Tungsten
    # reference render (dragon/reference-tungsten/README.md): rotation 90 puts +x at the
    # panorama's centre column, Tungsten's convention; 40 degrees horizontal fov at 4:3.
    "dragon-envmap": {
        "description": "The Stanford dragon (grey Lambertian, flat shaded) lit only by an "
                       "environment map, framed as the Tungsten reference render",
        "render": {"width": 640, "height": 480, "spp": 64, "max_depth": 256},
        "camera": {"look_from": [0, 6, 28], "look_at": [0, 4.5, 0], "up": [0, 1, 0],
                   "vfov": 30.5369432627651},
        "background": {"type": "environment", "file": "textures/tungsten_envmap.hdr",
                       "rotation": 90},
        "materials": {"grey": {"type": "lambertian", "albedo": 0.5}},
        "objects": [{"type": "mesh", "file": "meshes/dragon_100k.obj", "material": "grey",
                     "normals": "flat"}],
    },
    "materials": materials(),
}


def dimples_normal_map(path, size=64, cells=4):
    """A tangent-space normal map (8-bit RGB PNG, to be read raw) of size x size texels: a grid
    of cells x cells hemispherical dimples, n = (-dx, -dy, sqrt(1 - dx^2 - dy^2)) inside each
    dimple (dx, dy its offset from the centre along +u and +v, over its radius), n = +z around
    them; encoded (n + 1) / 2, OpenGL's convention (green along +v, row 0 at the top)."""
    cell = size // cells
    radius = 0.42 * cell
    rows = []
    for row in range(size):
        line = bytearray([0])  # PNG filter: none
        for col in range(size):
            dx = ((col % cell) + 0.5 - cell / 2) / radius
            dy = -((row % cell) + 0.5 - cell / 2) / radius  # v grows upwards
            r2 = dx * dx + dy * dy
            n = (-dx, -dy, math.sqrt(1 - r2)) if r2 < 1 else (0.0, 0.0, 1.0)
            line += bytes(min(255, max(0, round((c + 1) / 2 * 255))) for c in n)
        rows.append(bytes(line))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(b"".join(rows), 9)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def main():
    dimples_normal_map(os.path.join(HERE, "textures", "dimples_normal.png"))
    for name, scene in SCENES.items():
        with open(os.path.join(HERE, name + ".json"), "w") as f:
            json.dump(scene, f, indent=1)
            f.write("\n")


if __name__ == "__main__":
    main()
