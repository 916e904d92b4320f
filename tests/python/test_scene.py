"""Scenes: loaded in every format with errors that name the file and place, or built with the
builders into the same scene as a file."""
import json

import numpy as np
import pytest

import wavetrace as wt
from conftest import SCENES


def cornell_in_python():
    """scenes/cornell.json, built with the builders in the file's order."""
    s = wt.Scene()
    s.render = wt.RenderSettings(width=600, height=600, spp=64, max_depth=50)
    s.camera = wt.Camera(look_from=(278, 278, -800), look_at=(278, 278, 0), up=(0, 1, 0),
                         vfov=40)
    s.background = wt.Background(radiance=(0, 0, 0))

    def lambertian(rgb):
        return s.add_material(wt.Material(kind=wt.MaterialKind.Lambertian,
                                          albedo=s.add_solid(rgb)))
    red = lambertian((0.65, 0.05, 0.05))
    white = lambertian((0.73, 0.73, 0.73))
    green = lambertian((0.12, 0.45, 0.15))
    light = s.add_material(wt.Material(kind=wt.MaterialKind.DiffuseLight,
                                       emission=s.add_solid((15, 15, 15))))
    for q, u, v, m in [((555, 0, 0), (0, 0, 555), (0, 555, 0), green),
                       ((0, 0, 555), (0, 0, -555), (0, 555, 0), red),
                       ((213, 554, 227), (130, 0, 0), (0, 0, 105), light),
                       ((0, 555, 0), (555, 0, 0), (0, 0, 555), white),
                       ((0, 0, 555), (555, 0, 0), (0, 0, -555), white),
                       ((555, 0, 555), (-555, 0, 0), (0, 555, 0), white)]:
        s.add_quad(wt.Quad(q=q, u=u, v=v, material=m))
    for size, degrees, offset in [((165, 330, 165), 15, (265, 0, 295)),
                                  ((165, 165, 165), -18, (130, 0, 65))]:
        to_world = wt.Transform.translate(offset) * wt.Transform.rotate((0, 1, 0), degrees)
        s.add_box((0, 0, 0), size, white, to_world=to_world)
    return s


def test_a_scene_built_in_python_renders_as_the_same_scene_from_json(cornell):
    built = cornell_in_python()
    assert built.info()["primitives"] == cornell.info()["primitives"] == 18
    for engine in ("wavefront", "megakernel"):
        a = wt.render(built, width=40, height=40, spp=4, engine=engine)
        b = wt.render(cornell, width=40, height=40, spp=4, engine=engine)
        assert np.array_equal(a, b)


def test_info_counts_what_the_scene_holds(cornell):
    info = cornell.info()
    assert info["quads"] == 18 and info["emitters"] == 1 and info["materials"] == 4
    assert info["path"].endswith("cornell.json")
    lo, hi = info["bounds"]
    assert lo[0] == pytest.approx(0, abs=1e-3) and hi[1] == pytest.approx(555, abs=1e-3)


@pytest.mark.parametrize("name", ["cornell.json", "cornell-box.pbrt", "dragon.json",
                                  "materials.json", "everything.json"])
def test_every_format_loads(name):
    scene = wt.load_scene(SCENES / name)
    assert scene.info()["primitives"] > 0
    scene.check()


def test_a_bad_scene_raises_naming_the_file_and_place(tmp_path):
    bad = tmp_path / "bad.json"
    doc = json.loads((SCENES / "cornell.json").read_text())
    doc["objects"].append({"type": "sphere", "center": [0, 0, 0], "radius": -1,
                           "material": "white"})
    bad.write_text(json.dumps(doc))
    with pytest.raises(wt.SceneError, match=r"bad\.json: /objects/8/radius"):
        wt.load_scene(bad)
    pbrt = tmp_path / "bad.pbrt"
    pbrt.write_text('WorldBegin\nShape "sphere" "float radius" [ "x" ]\n')
    with pytest.raises(wt.SceneError, match=r"bad\.pbrt:2"):
        wt.load_scene(pbrt)
    with pytest.raises(wt.SceneError, match="missing.json"):
        wt.load_scene(tmp_path / "missing.json")


def test_warnings_become_python_warnings(tmp_path):
    f = tmp_path / "warn.pbrt"
    f.write_text('Camera "realistic"\nWorldBegin\nShape "sphere"\n')
    with pytest.warns(UserWarning, match="realistic"):
        wt.load_scene(f)


def test_a_built_scene_is_checked_before_it_is_rendered():
    s = wt.Scene()
    s.add_sphere(wt.Sphere(center=(0, 0, -3), radius=1, material=5))
    with pytest.raises(wt.SceneError, match="sphere 0: names no material"):
        wt.render(s, width=8, height=8, spp=1)
    s = wt.Scene()
    m = s.add_material(wt.Material(kind=wt.MaterialKind.Lambertian))  # no albedo
    s.add_sphere(wt.Sphere(center=(0, 0, -3), radius=1, material=m))
    with pytest.raises(wt.SceneError, match="albedo is needed"):
        s.check()
    with pytest.raises(TypeError, match="no attribute 'colour'"):
        wt.Material(colour=(1, 0, 0))


def test_a_blend_built_in_python_renders_as_the_same_blend_from_json(tmp_path):
    (tmp_path / "b.json").write_text(json.dumps({
        "camera": {"look_from": [0, 0, 5], "look_at": [0, 0, 0]},
        "background": {"type": "constant", "radiance": [1, 1, 1]},
        "materials": {"red": {"type": "lambertian", "albedo": [0.8, 0.1, 0.1]},
                      "m": {"type": "blend", "weight": 0.25,
                            "materials": ["red", {"type": "mirror"}]}},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]}))
    s = wt.Scene()
    s.camera = wt.Camera(look_from=(0, 0, 5), look_at=(0, 0, 0))
    s.background = wt.Background(radiance=(1, 1, 1))
    red = s.add_material(wt.Material(kind=wt.MaterialKind.Lambertian,
                                      albedo=s.add_solid((0.8, 0.1, 0.1))))
    mirror = s.add_material(wt.Material(kind=wt.MaterialKind.Mirror, albedo=s.add_solid((1, 1, 1))))
    blend = s.add_material(wt.Material(kind=wt.MaterialKind.Blend, blend_materials=(red, mirror),
                                       blend_weight=0.25))
    s.add_sphere(wt.Sphere(center=(0, 0, 0), radius=1, material=blend))
    a = wt.render(s, width=16, height=16, spp=4)
    b = wt.render(wt.load_scene(tmp_path / "b.json"), width=16, height=16, spp=4)
    assert np.array_equal(a, b)
    s.add_material(wt.Material(kind=wt.MaterialKind.Blend, blend_materials=(blend, 99)))
    with pytest.raises(wt.SceneError, match="must be added before it"):
        s.check()


def test_a_mesh_from_arrays_is_hit_where_it_lies():
    s = wt.Scene()
    m = s.add_material(wt.Material(kind=wt.MaterialKind.Lambertian,
                                   albedo=s.add_solid((1, 1, 1))))
    positions = np.array([[-1, -1, -2], [1, -1, -2], [1, 1, -2], [-1, 1, -2]], np.float32)
    indices = np.array([[0, 1, 2], [0, 2, 3], [0, 0, 1]])  # the last one is degenerate
    assert s.add_mesh(positions, indices, m, name="square") == 1
    hits = wt.Bvh(s).intersect(np.zeros((2, 3)), np.array([[0.5, -0.5, -1], [3, 0, -1]]))
    assert hits.hit.tolist() == [True, False]
    assert hits.t[0] == pytest.approx(2) and hits.kind[0] == 0 and hits.prim[0] == 0


def test_mesh_attributes_from_arrays_render_as_the_same_ply_from_json(tmp_path):
    positions = [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]
    faces = [[0, 1, 2], [0, 0, 1], [0, 2, 3]]  # the second is degenerate: skipped
    face_color = [[0.9, 0.1, 0.1], [5, 5, 5], [0.1, 0.1, 0.9]]
    vertex_weight = [0.0, 0.25, 0.5, 1.0]
    ply = ("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
           "property float z\nproperty float weight_0\nelement face 3\n"
           "property list uchar int vertex_indices\nproperty float color_r\n"
           "property float color_g\nproperty float color_b\nend_header\n")
    ply += "".join(f"{x} {y} {z} {w}\n" for (x, y, z), w in zip(positions, vertex_weight))
    ply += "".join(f"3 {a} {b} {c} {r} {g} {bl}\n" for (a, b, c), (r, g, bl) in zip(faces, face_color))
    (tmp_path / "m.ply").write_text(ply)
    (tmp_path / "m.json").write_text(json.dumps({
        "camera": {"look_from": [0, 0, 3], "look_at": [0, 0, 0]},
        "background": {"type": "constant", "radiance": [1, 1, 1]},
        "materials": {
            "face": {"type": "lambertian",
                     "albedo": {"type": "mesh_attribute", "name": "face_color_color"}},
            "m": {"type": "blend", "weight": {"type": "mesh_attribute", "name": "vertex_weight"},
                  "materials": ["face", {"type": "lambertian", "albedo": [0.2, 0.8, 0.2]}]}},
        "objects": [{"type": "mesh", "file": "m.ply", "material": "m"}]}))
    s = wt.Scene()
    s.camera = wt.Camera(look_from=(0, 0, 3), look_at=(0, 0, 0))
    s.background = wt.Background(radiance=(1, 1, 1))
    face = s.add_material(wt.Material(
        kind=wt.MaterialKind.Lambertian,
        albedo=s.add_texture(wt.Texture(kind=wt.TextureKind.MeshAttribute,
                                        attribute="face_color_color"))))
    green = s.add_material(wt.Material(kind=wt.MaterialKind.Lambertian,
                                       albedo=s.add_solid((0.2, 0.8, 0.2))))
    weight = s.add_texture(wt.Texture(kind=wt.TextureKind.MeshAttribute, attribute="vertex_weight"))
    blend = s.add_material(wt.Material(kind=wt.MaterialKind.Blend, blend_materials=(face, green),
                                       blend_weight_texture=weight))
    attributes = {"face_color_color": np.array(face_color, np.float32),
                  "vertex_weight": np.array(vertex_weight, np.float32)}
    assert s.add_mesh(np.array(positions, np.float32), np.array(faces), blend, name="m.ply",
                      attributes=attributes) == 1
    a = wt.render(s, width=16, height=16, spp=4)
    b = wt.render(wt.load_scene(tmp_path / "m.json"), width=16, height=16, spp=4)
    assert np.array_equal(a, b)
    assert a[8, 4, 2] > a[8, 4, 0]  # the left half is the blue face's
    with pytest.raises(ValueError, match="one value per triangle"):
        s.add_mesh(np.array(positions, np.float32), np.array(faces), blend,
                   attributes={"face_x": np.zeros(2, np.float32)})
    s.add_sphere(wt.Sphere(center=(0, 0, -5), radius=1, material=face))
    with pytest.raises(wt.SceneError, match="sphere 0: its material reads a mesh attribute"):
        s.check()


def test_a_product_texture_built_in_python_renders_as_in_json(tmp_path):
    (tmp_path / "p.json").write_text(json.dumps({
        "camera": {"look_from": [0, 0, 5], "look_at": [0, 0, 0]},
        "background": {"type": "constant", "radiance": [1, 1, 1]},
        "materials": {"m": {"type": "lambertian", "albedo": {"type": "product", "factors": [
            [0.9, 0.5, 0.2], {"type": "checker", "scale": 0.5, "even": 1, "odd": 0.3}]}}},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]}))
    s = wt.Scene()
    s.camera = wt.Camera(look_from=(0, 0, 5), look_at=(0, 0, 0))
    s.background = wt.Background(radiance=(1, 1, 1))
    tint = s.add_solid((0.9, 0.5, 0.2))
    checker = s.add_texture(wt.Texture(kind=wt.TextureKind.Checker, scale=0.5,
                                       even=s.add_solid((1, 1, 1)),
                                       odd=s.add_solid((0.3, 0.3, 0.3))))
    product = s.add_texture(wt.Texture(kind=wt.TextureKind.Product, factors=(tint, checker)))
    s.add_sphere(wt.Sphere(center=(0, 0, 0), radius=1,
                           material=s.add_material(wt.Material(kind=wt.MaterialKind.Lambertian,
                                                               albedo=product))))
    a = wt.render(s, width=16, height=16, spp=4)
    b = wt.render(wt.load_scene(tmp_path / "p.json"), width=16, height=16, spp=4)
    assert np.array_equal(a, b)


def test_an_asset_root_confines_the_files_read(tmp_path):
    assert wt.load_scene(SCENES / "bunny.json", asset_root=SCENES).info()["triangles"] > 0
    with pytest.raises(wt.SceneError, match="outside the asset root"):
        wt.load_scene(SCENES / "bunny.json", asset_root=tmp_path)


def test_an_environment_map_and_the_medium_rule_are_set_as_in_json(tmp_path):
    (tmp_path / "s.json").write_text(json.dumps({
        "camera": {"look_from": [0, 0, 5], "look_at": [0, 0, 0]},
        "background": {"type": "environment", "file": "sky.pfm", "mapping": "equal_area",
                       "to_world": [[1, 0, 0], [0, 0, 1], [0, -1, 0]]},
        "medium_boundaries": "interface", "objects": []}))
    sky = np.ones((4, 4, 3), dtype=np.float32)
    wt.write_image(str(tmp_path / "sky.pfm"), sky)
    s = wt.load_scene(tmp_path / "s.json")
    assert s.background.mapping == wt.Background.Mapping.EqualArea
    assert np.allclose(s.background.to_world, [[1, 0, 0], [0, 0, 1], [0, -1, 0]])
    assert s.medium_boundaries == wt.MediumBoundaries.Interface
    b = wt.Background(kind=wt.Background.Kind.Environment, to_world=None)
    assert b.to_world is None and b.mapping == wt.Background.Mapping.LatLong


def test_sphere_mappings_and_flipped_quads_are_fields():
    s = wt.Scene()
    m = s.add_material(wt.Material(kind=wt.MaterialKind.Lambertian,
                                   albedo=s.add_solid((1, 1, 1))))
    sphere = wt.Sphere(center=(0, 0, 0), radius=1, material=m, mapping=wt.SphereMapping.ZUp)
    assert sphere.mapping == wt.SphereMapping.ZUp
    assert wt.Sphere().mapping == wt.SphereMapping.YUp
    assert wt.Quad(q=(0, 0, 0), u=(1, 0, 0), v=(0, 1, 0), material=m, flip_v=True).flip_v
    s.add_sphere(sphere)
    s.check()
    assert s.geometric_side_test
    s.geometric_side_test = False
    assert not s.geometric_side_test


def test_a_medium_of_per_channel_density_renders_as_in_json(tmp_path):
    path = tmp_path / "tinted.json"
    path.write_text(json.dumps({
        "camera": {"look_from": [0, 0, -4], "look_at": [0, 0, 0], "vfov": 40},
        "background": [1, 1, 1],
        "media": {"tinted": {"density": [0.3, 2.0, 0.6], "albedo": [0.8, 0.8, 0.8]}},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "interior": "tinted"}]}))
    from_json = wt.load_scene(path)
    s = wt.Scene()
    s.camera = wt.Camera(look_from=(0, 0, -4), look_at=(0, 0, 0), up=(0, 1, 0), vfov=40)
    s.background = wt.Background(radiance=(1, 1, 1))
    m = s.add_medium("tinted", (0.3, 2.0, 0.6), s.add_solid((0.8, 0.8, 0.8)))
    s.add_sphere(wt.Sphere(center=(0, 0, 0), radius=1, material=s.interface_material(),
                           interior=m))
    a = wt.render(s, width=16, height=16, spp=4)
    assert np.array_equal(a, wt.render(from_json, width=16, height=16, spp=4))
    # Through the sphere's middle green, the densest, is the darkest.
    r, g, b = a[8, 8]
    assert g < b < r


def test_an_orthographic_camera_renders_as_in_json(tmp_path):
    # A unit sphere seen by parallel rays through a 4 x 2 film: a disk of radius 1 centred,
    # a quarter of the image's width across.
    path = tmp_path / "ortho.json"
    path.write_text(json.dumps({
        "camera": {"type": "orthographic", "look_from": [0, 0, -4], "look_at": [0, 0, 0],
                   "view_height": 2},
        "background": [1, 1, 1],
        "materials": {"black": {"type": "lambertian", "albedo": [0, 0, 0]}},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "black"}]}))
    from_json = wt.load_scene(path)
    s = wt.Scene()
    s.camera = wt.Camera(look_from=(0, 0, -4), look_at=(0, 0, 0), up=(0, 1, 0),
                         orthographic=True, view_height=2)
    s.background = wt.Background(radiance=(1, 1, 1))
    black = s.add_material(wt.Material(name="black", albedo=s.add_solid((0, 0, 0))))
    s.add_sphere(wt.Sphere(center=(0, 0, 0), radius=1, material=black))
    a = wt.render(s, width=32, height=16, spp=4)
    assert np.array_equal(a, wt.render(from_json, width=32, height=16, spp=4))
    row = a[8, :, 0]
    assert row[16] == 0 and row[9] == 0 and row[22] == 0  # inside the disk, |x| < 1
    assert row[6] == 1 and row[25] == 1  # outside it, |x| > 1.1


def test_a_spot_projecting_a_texture_renders_as_in_json(tmp_path):
    # A 2 x 2 slide (pfm rows bottom first on disk; wavetrace's images are row 0 at the top)
    # projected by a spot onto a floor, built both ways with the texture's wraps set.
    slide = np.array([[[1, 0.2, 0.2], [0.2, 1, 0.2]], [[0.2, 0.2, 1], [1, 1, 0.2]]],
                     dtype=np.float32)
    wt.write_image(str(tmp_path / "slide.pfm"), slide)
    path = tmp_path / "spot.json"
    path.write_text(json.dumps({
        "camera": {"look_from": [0, 3, -3], "look_at": [0, 0, 0], "vfov": 60},
        "materials": {"floor": {"type": "lambertian", "albedo": 0.8}},
        "objects": [{"type": "quad", "q": [-3, 0, -3], "u": [0, 0, 6], "v": [6, 0, 0],
                     "material": "floor"}],
        "lights": [{"type": "spot", "position": [0, 2, 0], "look_at": [0, 0, 0],
                    "intensity": 10, "cutoff": 40,
                    "texture": {"type": "image", "file": "slide.pfm", "filter": "nearest",
                                "wrap": ["clamp", "mirror"]},
                    "up": [0, 0, 1]}]}))
    from_json = wt.load_scene(path)
    s = wt.Scene()
    s.camera = wt.Camera(look_from=(0, 3, -3), look_at=(0, 0, 0), up=(0, 1, 0), vfov=60)
    floor = s.add_material(wt.Material(kind=wt.MaterialKind.Lambertian,
                                       albedo=s.add_solid((0.8, 0.8, 0.8))))
    s.add_quad(wt.Quad(q=(-3, 0, -3), u=(0, 0, 6), v=(6, 0, 0), material=floor))
    tex = s.add_texture(wt.Texture(kind=wt.TextureKind.Image,
                                   image=s.add_image(wt.read_image(str(tmp_path / "slide.pfm"))),
                                   filter=wt.TextureFilter.Nearest, wrap_u=wt.TextureWrap.Clamp,
                                   wrap_v=wt.TextureWrap.Mirror))
    s.add_light(wt.Light(kind=wt.Light.Kind.Spot, position=(0, 2, 0), direction=(0, -1, 0),
                         intensity=(10, 10, 10), cutoff_degrees=40, falloff_start_degrees=30,
                         texture=tex, up=(0, 0, 1)))
    settings = dict(width=16, height=16, spp=4, strategy="nee", max_depth=2)
    a = wt.render(s, **settings)
    assert np.array_equal(a, wt.render(from_json, **settings))
    # The slide's four colours land in four quadrants of the lit floor.
    assert len({tuple(np.round(a[y, x] / a[y, x].max(), 2)) for y in (6, 9) for x in (6, 9)}) == 4
