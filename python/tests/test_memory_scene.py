"""Scenes built in memory: equal to the same scene read from a glTF file (colour, depth and ids),
and moving an instance between frames (temporal reuse redraws it alone, the image stays exact)."""
import base64
import json
import struct
import zlib

import numpy as np
import pytest

import frugal


def box_arrays(size=1.0):
    """A cube's 8 corners and 12 counter-clockwise triangles (outward)."""
    s = size / 2
    positions = np.array([[x, y, z] for x in (-s, s) for y in (-s, s) for z in (-s, s)], dtype=np.float32)
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    indices = np.array([t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))], dtype=np.uint32)
    return positions, indices


def grid_arrays(n=6):
    """A wavy n x n grid in the xy plane with colours and texture coordinates."""
    u, v = np.meshgrid(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1))
    positions = np.stack([u * 2 - 1, v * 2 - 1, 0.15 * np.sin(6 * u) * np.cos(5 * v)], -1).reshape(-1, 3)
    colors = np.stack([u, v, 1 - u, np.ones_like(u)], -1).reshape(-1, 4)
    uvs = np.stack([u * 2, v * 2], -1).reshape(-1, 2)
    i = np.arange(n)[:, None] * (n + 1) + np.arange(n)[None, :]
    quads = np.stack([i, i + 1, i + n + 2, i + n + 1], -1).reshape(-1, 4)
    indices = np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
    return positions.astype(np.float32), indices.astype(np.uint32), colors.astype(np.float32), uvs.astype(np.float32)


def checker(size=8):
    y, x = np.mgrid[0:size, 0:size]
    on = ((x + y) % 2).astype(bool)
    image = np.zeros((size, size, 4), dtype=np.uint8)
    image[on], image[~on] = (230, 180, 40, 255), (30, 60, 200, 255)
    return image


def png_bytes(rgba):
    height, width, _ = rgba.shape
    raw = b"".join(b"\0" + rgba[y].tobytes() for y in range(height))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def write_gltf(path, meshes, instances, texture=None, camera=None):
    """A glTF file of `meshes` [(positions, indices, colors, uvs)], each with its own material (the
    second textured when `texture` is given), `instances` [(mesh, 4x4 matrix)], and optionally a
    camera ((eye), yfov radians) looking down -z."""
    blob, views, accessors, gltf_meshes = b"", [], [], []

    def add(array, target, kind, component):
        nonlocal blob
        data = np.ascontiguousarray(array).tobytes()
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
        entry = {"bufferView": len(views) - 1, "componentType": component, "count": len(array), "type": kind}
        if kind == "VEC3" and component == 5126:
            entry["min"], entry["max"] = array.min(0).tolist(), array.max(0).tolist()
        accessors.append(entry)
        blob += data + b"\0" * (-len(data) % 4)
        return len(accessors) - 1

    materials = []
    for m, (positions, indices, colors, uvs) in enumerate(meshes):
        attributes = {"POSITION": add(positions, 34962, "VEC3", 5126)}
        if colors is not None:
            attributes["COLOR_0"] = add(colors, 34962, "VEC4", 5126)
        if uvs is not None:
            attributes["TEXCOORD_0"] = add(uvs, 34962, "VEC2", 5126)
        primitive = {"attributes": attributes, "indices": add(indices.reshape(-1), 34963, "SCALAR", 5125),
                     "material": m}
        gltf_meshes.append({"primitives": [primitive]})
        material = {"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.8 - 0.3 * m, 0.7, 1.0]},
                    "doubleSided": m == 1}
        if texture is not None and m == 1:
            material["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
        materials.append(material)
    nodes = [{"mesh": mesh, "matrix": np.asarray(matrix, dtype=float).T.reshape(-1).tolist()}
             for mesh, matrix in instances]
    gltf = {"asset": {"version": "2.0"}, "scene": 0, "meshes": gltf_meshes, "materials": materials,
            "accessors": accessors, "bufferViews": views, "nodes": nodes,
            "buffers": [{"byteLength": len(blob),
                         "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}]}
    if texture is not None:
        gltf["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png_bytes(texture)).decode()}]
        gltf["textures"] = [{"source": 0}]
    if camera is not None:
        eye, yfov = camera
        nodes.append({"camera": 0, "translation": list(eye)})
        gltf["cameras"] = [{"type": "perspective", "perspective": {"yfov": yfov, "znear": 0.1}}]
    gltf["scenes"] = [{"nodes": list(range(len(nodes)))}]
    path.write_text(json.dumps(gltf))
    return path


def translation(x, y, z, turn=0.0):
    m = np.eye(4)
    c, s = np.cos(turn), np.sin(turn)
    m[:3, :3] = [[c, 0, s], [0, 1, 0], [-s, 0, c]]
    m[:3, 3] = (x, y, z)
    return m


INSTANCES = [(0, translation(-1.2, 0, 0, 0.5)), (1, translation(0.8, 0.2, -0.5, -0.4)), (0, translation(0.3, -0.9, 0.4))]


def memory_scene():
    scene = frugal.Scene()
    texture = scene.add_texture(checker())
    box, (grid, grid_indices, colors, uvs) = box_arrays(), grid_arrays()
    plain = scene.add_material((0.9, 0.8, 0.7, 1.0))
    textured = scene.add_material((0.9, 0.5, 0.7, 1.0), texture=texture, double_sided=True)
    meshes = [scene.add_mesh(*box, material=plain),
              scene.add_mesh(grid, grid_indices, colors=colors, uvs=uvs, material=textured)]
    nodes = [scene.add_instance(meshes[mesh], matrix) for mesh, matrix in INSTANCES]
    return scene, nodes


def test_memory_scene_equals_the_gltf_file(tmp_path):
    scene, nodes = memory_scene()
    assert nodes == [0, 1, 2] and scene.instance_count == 3
    grid, grid_indices, colors, uvs = grid_arrays()
    path = write_gltf(tmp_path / "same.gltf", [(*box_arrays(), None, None), (grid, grid_indices, colors, uvs)],
                      INSTANCES, texture=checker())
    loaded = frugal.load(str(path))
    assert loaded.triangle_count == scene.triangle_count == 2 * 12 + len(grid_indices)
    camera = frugal.Camera.look_at((0.5, 1.5, 4.0), (0, 0, 0), fov=50)
    for backend in ("auto", "software"):
        a = frugal.Renderer(scene, size=(160, 120), ids=True, backend=backend).render(camera)
        b = frugal.Renderer(loaded, size=(160, 120), ids=True, backend=backend).render(camera)
        np.testing.assert_array_equal(a.color, b.color)
        np.testing.assert_array_equal(a.depth, b.depth)
        np.testing.assert_array_equal(a.ids, b.ids)
        assert len(np.unique(a.ids)) > 20, "every instance is in view"


def test_maps_are_drawn_and_listed():
    """A material with every map: listed as given, drawn alike by GL and the software reference (the
    mesh's tangents generated when drawn), and unlike the same material without the maps."""
    rng = np.random.default_rng(38)
    maps = [rng.integers(0, 256, (8, 8, 4), dtype=np.uint8) for _ in range(3)]
    grid, grid_indices, _, uvs = grid_arrays()
    camera = frugal.Camera.look_at((0.5, 1.5, 4.0), (0, 0, 0), fov=50)

    def render(with_maps, backend):
        scene = frugal.Scene()
        options = {}
        if with_maps:
            data = [scene.add_texture(m, srgb=False) for m in maps]
            options = dict(metallic_roughness_texture=data[0], occlusion_texture=data[1], occlusion_strength=0.5,
                           emissive_texture=scene.add_texture(checker()), normal_texture=data[2], normal_scale=2.0)
        material = scene.add_material((0.9, 0.6, 0.3), metallic=0.5, roughness=0.8, emissive=(0.2, 0.2, 0.2),
                                      **options)
        if with_maps:
            listed = scene.materials[material]
            assert (listed["metallic_roughness_texture"], listed["occlusion_texture"],
                    listed["normal_texture"]) == (0, 1, 2)
            assert listed["emissive_texture"] == 3
            assert listed["occlusion_strength"] == 0.5 and listed["normal_scale"] == 2.0
        scene.add_instance(scene.add_mesh(grid, grid_indices, uvs=uvs, material=material))
        return frugal.Renderer(scene, size=(160, 120), backend=backend).render(camera).color

    mapped = render(True, "auto")
    assert np.abs(mapped.astype(int) - render(True, "software")).max() <= 1  # the stated tolerance
    assert (mapped != render(False, "auto")).any()


def test_alpha_modes_are_drawn_and_listed():
    """A masked grid with holes (vertex alphas against the cutoff) over a blended one over an opaque
    one: listed as given, drawn alike by GL and the software reference (colour within a step; ids
    exactly, a blended surface writing its own), and differently from the same scene all opaque."""
    grid, grid_indices, colors, _ = grid_arrays()
    rng = np.random.default_rng(40)
    alphas = np.concatenate([colors[:, :3], rng.uniform(0, 1, (len(grid), 1))], axis=1).astype(np.float32)
    camera = frugal.Camera.look_at((0.3, 0.5, 4.0), (0, 0, 0), fov=50)

    def render(alpha, backend):
        scene = frugal.Scene()
        modes = ("opaque", "blend", "mask") if alpha else ("opaque",) * 3
        for k, mode in enumerate(modes):
            material = scene.add_material((0.9, 0.5 + 0.2 * k, 0.3, 0.6), alpha=mode, alpha_cutoff=0.4,
                                          double_sided=True)
            listed = scene.materials[material]
            assert listed["alpha"] == mode and listed["alpha_cutoff"] == np.float32(0.4)
            mesh = scene.add_mesh(grid, grid_indices, colors=alphas, material=material)
            scene.add_instance(mesh, translation(0.1 * k, 0.05 * k, 0.5 * k))
        return frugal.Renderer(scene, size=(160, 120), backend=backend, ids=True).render(camera)

    gl, software = render(True, "auto"), render(True, "software")
    assert np.abs(gl.color.astype(int) - software.color).max() <= 1
    np.testing.assert_array_equal(gl.ids, software.ids)
    assert (gl.color != render(False, "auto").color).any()


def test_specular_glossiness_is_drawn_and_listed():
    """A KHR_materials_pbrSpecularGlossiness material with its map: listed as given, drawn alike by GL
    and the software reference, and unlike the metallic-roughness material of the same colour."""
    grid, grid_indices, _, uvs = grid_arrays()
    texels = np.random.default_rng(41).integers(0, 256, (8, 8, 4), np.uint8)
    camera = frugal.Camera.look_at((0.3, 0.8, 3.5), (0, 0, 0), fov=50)

    def render(specular, backend):
        scene = frugal.Scene()
        options = {}
        if specular:
            options = dict(specular=(0.9, 0.6, 0.2), glossiness=0.7,
                           specular_glossiness_texture=scene.add_texture(texels, srgb=False))
        material = scene.add_material((0.4, 0.5, 0.8), metallic=0.0, roughness=0.5, **options)
        listed = scene.materials[material]
        assert (listed["specular"] is not None) == specular
        if specular:
            assert listed["specular_glossiness_texture"] == 0 and listed["glossiness"] == np.float32(0.7)
        scene.add_instance(scene.add_mesh(grid, grid_indices, uvs=uvs, material=material))
        return frugal.Renderer(scene, size=(160, 120), backend=backend).render(camera).color

    glossy = render(True, "auto")
    assert np.abs(glossy.astype(int) - render(True, "software")).max() <= 1
    assert (glossy != render(False, "auto")).any()


def test_clear_coat_is_drawn_and_listed():
    """A KHR_materials_clearcoat coat with its three maps: listed as given, drawn alike by GL and the
    software reference, unlike the uncoated material; a coat of 0 draws as none."""
    grid, grid_indices, _, uvs = grid_arrays()
    texels = np.random.default_rng(43).integers(0, 256, (8, 8, 4), np.uint8)
    camera = frugal.Camera.look_at((0.3, 0.8, 3.5), (0, 0, 0), fov=50)

    def render(coat, backend):
        scene = frugal.Scene()
        texture = scene.add_texture(texels, srgb=False)
        options = dict(clearcoat=coat, clearcoat_roughness=0.2, clearcoat_texture=texture,
                       clearcoat_roughness_texture=texture, clearcoat_normal_texture=texture,
                       clearcoat_normal_scale=0.5)
        material = scene.add_material((0.5, 0.02, 0.01), metallic=0.0, roughness=0.5, **options)
        listed = scene.materials[material]
        assert listed["clearcoat"] == np.float32(coat) and listed["clearcoat_roughness"] == np.float32(0.2)
        assert listed["clearcoat_texture"] == listed["clearcoat_normal_texture"] == texture
        assert listed["clearcoat_normal_scale"] == 0.5
        scene.add_instance(scene.add_mesh(grid, grid_indices, uvs=uvs, material=material))
        return frugal.Renderer(scene, size=(160, 120), backend=backend).render(camera).color

    coated = render(1.0, "auto")
    assert np.abs(coated.astype(int) - render(1.0, "software")).max() <= 1
    uncoated = render(0.0, "auto")
    assert (coated != uncoated).any()
    with pytest.raises(frugal.InputError, match="clear coat 1.5 is not in"):
        frugal.Scene().add_material(clearcoat=1.5)


def test_mipmaps_average_a_minified_texture():
    """A one-texel checker tiled far more often than the grid has pixels: without mipmaps the base
    level aliases into noise, with them each pixel takes the average of its footprint (a flat colour
    between the two); GL and the software reference agree on both. Bad filters are refused."""
    grid, grid_indices, _, uvs = grid_arrays()
    camera = frugal.Camera.look_at((0.3, 0.8, 3.5), (0, 0, 0), fov=50)

    def render(mipmaps, backend):
        scene = frugal.Scene()
        texture = scene.add_texture(checker(64), min_filter="nearest" if mipmaps == "none" else "linear",
                                    mipmaps=mipmaps)
        material = scene.add_material(texture=texture, metallic=0.0, roughness=1.0, unlit=True)
        scene.add_instance(scene.add_mesh(grid, grid_indices, uvs=uvs * 16, material=material))
        return frugal.Renderer(scene, size=(160, 120), backend=backend, ids=True).render(camera)

    aliased, averaged = render("none", "auto").color, render("linear", "auto")
    covered = averaged.ids > 0
    averaged = averaged.color
    assert covered.sum() > 4000, "the grid fills a quarter of the image"
    assert np.abs(aliased.astype(int) - render("none", "software").color).max() <= 1
    assert np.abs(averaged.astype(int) - render("linear", "software").color).max() <= 1
    # Aliased, neighbouring pixels jump between the checker's two colours; averaged, they barely move.
    assert np.abs(np.diff(aliased[..., 2].astype(int), axis=1))[covered[:, 1:]].mean() > 40
    assert np.abs(np.diff(averaged[..., 2].astype(int), axis=1))[covered[:, 1:]].mean() < 5
    with pytest.raises(frugal.InputError, match="mipmaps: 'tri' is not a mipmap filter"):
        frugal.Scene().add_texture(checker(), mipmaps="tri")
    with pytest.raises(frugal.InputError, match="min_filter: 'cubic' is not a filter"):
        frugal.Scene().add_texture(checker(), min_filter="cubic")


def test_punctual_lights_light_the_scene_and_move_with_their_node():
    """add_light: a spot light over the grid lights it instead of the default light, alike on GL and
    the software reference; moving its node moves the light; bad lights are refused."""
    grid, grid_indices, _, _ = grid_arrays()
    camera = frugal.Camera.look_at((0.3, 0.8, 3.5), (0, 0, 0), fov=50)
    above = np.array([[1, 0, 0, 0.3], [0, 1, 0, 0], [0, 0, 1, 1.5], [0, 0, 0, 1]], np.float32)  # -Z toward the grid

    def render(lit, backend, moved=False):
        scene = frugal.Scene()
        material = scene.add_material((0.8, 0.8, 0.8), metallic=0.0, roughness=0.5)
        scene.add_instance(scene.add_mesh(grid, grid_indices, material=material))
        if lit:
            node = scene.add_light("spot", color=(1, 0.8, 0.6), intensity=8.0, inner_cone=0.2, outer_cone=0.5,
                                   transform=above, name="lamp")
            if moved:
                shifted = above.copy()
                shifted[0, 3] = -0.6
                scene.set_transform(node, shifted)
        return frugal.Renderer(scene, size=(160, 120), backend=backend).render(camera).color

    spot = render(True, "auto")
    assert np.abs(spot.astype(int) - render(True, "software")).max() <= 1
    assert (spot != render(False, "auto")).any(axis=-1).mean() > 0.2, "the spot replaces the default light"
    assert (spot != render(True, "auto", moved=True)).any(axis=-1).mean() > 0.05, "the light moves with its node"
    with pytest.raises(frugal.InputError, match="kind: 'area' is not a kind of light"):
        frugal.Scene().add_light("area")
    with pytest.raises(frugal.InputError, match="inner cone angle 0.6 is not in \\[0, the outer angle 0.5\\)"):
        frugal.Scene().add_light("spot", inner_cone=0.6, outer_cone=0.5)
    with pytest.raises(frugal.InputError, match="intensity -1 is not finite and at least 0"):
        frugal.Scene().add_light(intensity=-1)


def test_given_tangents_are_kept_and_drawn():
    """Tangents given to add_mesh are the mesh's (given back by mesh()), and a normal map is read in
    their basis: the same mesh with the tangents turned about the normal draws differently; GL and
    the software reference agree."""
    grid, grid_indices, _, uvs = grid_arrays()
    texels = np.random.default_rng(42).integers(0, 256, (8, 8, 4), np.uint8)
    camera = frugal.Camera.look_at((0.3, 0.8, 3.5), (0, 0, 0), fov=50)

    def render(tangent, backend):
        scene = frugal.Scene()
        normal_map = scene.add_texture(texels, srgb=False)
        material = scene.add_material((0.8, 0.7, 0.5), metallic=0.0, roughness=0.4, normal_texture=normal_map)
        tangents = np.tile(np.array(tangent, np.float32), (len(grid), 1))
        mesh = scene.add_mesh(grid, grid_indices, uvs=uvs, tangents=tangents, material=material)
        np.testing.assert_array_equal(scene.mesh(mesh)["tangents"], tangents)
        scene.add_instance(mesh)
        return frugal.Renderer(scene, size=(160, 120), backend=backend).render(camera).color

    along_u = render((1, 0, 0, 1), "auto")
    assert np.abs(along_u.astype(int) - render((1, 0, 0, 1), "software")).max() <= 1
    assert (along_u != render((0, 1, 0, -1), "auto")).any()
    scene = frugal.Scene()
    with pytest.raises(frugal.InputError, match=r"tangents: expected an \(N, 4\) array"):
        scene.add_mesh(grid, grid_indices, tangents=np.ones((len(grid), 3), np.float32))


def test_mesh_arrays_round_trip():
    """mesh(i) gives back what add_mesh keeps: the triangles (reordered for the cache, ids kept)."""
    scene = frugal.Scene()
    grid, indices, colors, uvs = grid_arrays()
    mesh = scene.mesh(scene.add_mesh(grid, indices, colors=colors, uvs=uvs))
    np.testing.assert_array_equal(mesh["positions"], grid)
    np.testing.assert_array_equal(np.sort(mesh["triangle_source"]), np.arange(len(indices)))
    np.testing.assert_array_equal(mesh["indices"], indices[mesh["triangle_source"]])
    assert mesh["normals"].shape == grid.shape and mesh["uvs"].shape == uvs.shape


def test_moving_an_instance_with_reuse_stays_exact():
    """An instance moved between frames through set_transform: reuse redraws what moved, and each
    frame equals a renderer without reuse given the same moves."""
    scene, nodes = memory_scene()
    camera = frugal.Camera.look_at((0.5, 1.5, 6.0), (0, 0, 0), fov=50)
    reuse = frugal.Renderer(scene, size=(160, 120), reuse=True, no_fallback=True, ids=True)
    plain = frugal.Renderer(scene, size=(160, 120), ids=True)
    modes, moved = [], []
    for i in range(6):
        if i >= 2:
            matrix = translation(0.3 - 0.1 * i, -0.9, 0.4)  # within the scene's envelope
            if i == 5:  # far outside it: the envelope grows, the depth range with it (a full frame)
                matrix = translation(0.3, -0.9, -12.0)
            reuse.set_transform(nodes[2], matrix)
            plain.set_transform(nodes[2], matrix)
        a, b = reuse.render(camera), plain.render(camera)
        np.testing.assert_array_equal(a.color, b.color)
        np.testing.assert_array_equal(a.ids, b.ids)
        stats = a.stats.reuse
        modes.append(stats.mode)
        moved.append(stats.instances.p_dd + stats.instances.p_sd)
    assert modes[2:5] == ["reuse"] * 3, modes
    assert moved[2:5] == [1, 1, 1], moved
    assert modes[5] == "full" and a.camera.zfar > 12.0


def test_instances_materials_and_ids_name_what_drew_each_pixel():
    """scene.instances maps an id image back to instances and triangles (the recipe of
    docs/python.md), and materials and world transforms are what was added."""
    scene, nodes = memory_scene()
    instances = scene.instances
    assert [(i["node"], i["mesh"]) for i in instances] == [(0, 0), (1, 1), (2, 0)]
    assert instances[0]["first_id"] == 1 and instances[1]["first_id"] == 1 + 12
    assert [m["double_sided"] for m in scene.materials] == [False, True] and scene.materials[1]["texture"] == 0
    np.testing.assert_allclose(scene.world_transform(nodes[1]), INSTANCES[1][1], atol=1e-6)

    frame = frugal.Renderer(scene, size=(160, 120), ids=True).render(frugal.Camera.look_at((0.5, 1.5, 4), (0, 0, 0)))
    ids = frame.ids
    first = np.array([i["first_id"] for i in instances])
    instance = np.searchsorted(first, ids, side="right") - 1  # -1 where ids == 0 (background)
    triangle = ids - first[np.maximum(instance, 0)]
    assert set(np.unique(instance[ids > 0])) == {0, 1, 2}
    counts = np.array([i["triangles"] for i in instances])
    assert (triangle[ids > 0] < counts[instance[ids > 0]]).all()


def test_points_and_lines_are_drawn_with_their_ids():
    """topology='lines' and 'points': one pixel wide, ids per segment and per point, drawn in the
    base colour plus the emission where there are no normals (the Khronos renderer's rule)."""
    scene = frugal.Scene()
    ring = np.array([[np.cos(a), np.sin(a), 0.0] for a in np.linspace(0, 2 * np.pi, 9)[:-1]], np.float32)
    material = scene.add_material((0.2, 0.4, 0.6, 1.0), emissive=(0.1, 0.0, 0.0))
    segments = np.array([[i, (i + 1) % 8] for i in range(8)], np.uint32)
    lines = scene.add_mesh(ring, segments, material=material, topology="lines")
    points = scene.add_mesh(ring * 0.5, np.arange(8), material=material, topology="points")
    scene.add_instance(lines)
    scene.add_instance(points)
    assert scene.mesh(lines)["topology"] == "lines" and scene.mesh(lines)["indices"].shape == (8, 2)
    assert scene.mesh(points)["indices"].shape == (8, 1)
    assert [i["primitives"] for i in scene.instances] == [8, 8]
    assert [i["triangles"] for i in scene.instances] == [0, 0]
    camera = frugal.Camera.look_at((0, 0, 3), (0, 0, 0), fov=60)
    frames = [frugal.Renderer(scene, size=(96, 96), ids=True, backend=b).render(camera)
              for b in ("auto", "software")]
    for frame in frames:
        ids = frame.ids[frame.ids > 0]
        assert set(np.unique(ids)) == set(range(1, 17))  # every segment and every point
        drawn = frame.color[frame.ids > 0][:, :3]
        # (0.1 + 0.2, 0.4, 0.6) encoded as rgb^(1/2.2)
        np.testing.assert_allclose(drawn, np.broadcast_to([148, 168, 202], drawn.shape), atol=1)
    np.testing.assert_array_equal(frames[0].ids, frames[1].ids)
    np.testing.assert_array_equal(frames[0].depth, frames[1].depth)
    with pytest.raises(ValueError, match="topology: 'quads' is not a topology"):
        scene.add_mesh(ring, segments, topology="quads")
    with pytest.raises(ValueError, match=r"indices: expected a \(T, 2\)"):
        scene.add_mesh(ring, np.zeros((2, 3), np.uint32), topology="lines")
