"""ctest `python-module`: the module `rsl` driven from Debian's python3.

It must give the `rsl` program's answers for the same scene file: the same
vertex colours, image and ground truth (bit for bit), the same error numbers
and light fit; poses set from Python must equal a scene file saying the same;
long calls must release the GIL; progress must reach a Python callable; bad
input must raise rsl.Error with the message the program prints.

Environment: PYTHONPATH (the built module), RSL_EXECUTABLE, RSL_SOURCE_DIR.
"""
import json
import os
import re
import shutil
import subprocess
import tempfile
import threading
import time
import unittest

import numpy as np

import rsl

RSL = os.environ["RSL_EXECUTABLE"]
GENERATED = os.path.join(os.environ["RSL_SOURCE_DIR"], "assets", "generated")
SUNSKY = os.path.join(GENERATED, "sunsky.exr")


def floor_obj(n, half):
    lines = [f"v {-half + 2 * half * i / n} 0 {-half + 2 * half * j / n}" for j in range(n + 1) for i in range(n + 1)]
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i + 1
            b, c = a + 1, a + n + 1
            lines += [f"f {a} {c} {b}", f"f {b} {c} {c + 1}"]
    return "\n".join(lines) + "\n"


def write_scene(folder, name, orb_transform=None, rotation=None):
    """The orb on a floor under the turning sun and sky, light precomputation (as tests/api/api_test_scene.h)."""
    if not os.path.exists(os.path.join(folder, "floor.obj")):
        with open(os.path.join(folder, "floor.obj"), "w") as f:
            f.write(floor_obj(32, 0.8))
    scene = {
        "name": "python-test",
        "parts": [{"name": "orb", "obj": os.path.join(GENERATED, "orb.obj"), "material": "steel",
                   "transform": orb_transform or {}},
                  {"name": "floor", "obj": "floor.obj", "material": "floor"}],
        "materials": {"steel": {"model": "phong", "kd": [0.3, 0.3, 0.32], "ks": [0.4, 0.4, 0.4], "exponent": 30},
                      "floor": {"model": "lambert", "albedo": [0.55, 0.53, 0.5]}},
        "environment": {"file": SUNSKY, "resolution": 12,
                        "rotation": rotation or {"axis": [0, 1, 0], "degrees": 30, "degrees_per_second": 40}},
        "camera": {"position": [0.9, 0.75, 1.3], "target": [0, 0.2, 0], "up": [0, 1, 0], "fov_degrees": 36,
                   "width": 96, "height": 72},
        "animation": {"start": 0, "end": 1, "fps": 24},
        "precompute": {"svdf": {"resolution": 8, "clusters": 16, "vectors": 4, "supersampling": 1},
                       "ovdf": {"shells": 4, "inner_radius": 0.4, "outer_radius": 6.0, "cube_resolution": 6,
                                "vdt_resolution": 8, "vectors": 4}},
    }
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
    return path


def run_rsl(*args):
    done = subprocess.run([RSL, *args], capture_output=True, text=True)
    return done.returncode, done.stdout + done.stderr


def number_after(text, label):
    return float(re.search(re.escape(label) + r"\s*([0-9.eE+-]+)", text).group(1))


class ModuleTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.mkdtemp(prefix="rsl-python-test.")
        cls.scene_file = write_scene(cls.folder, "scene.json")
        out = cls.folder
        status, text = run_rsl("render", cls.scene_file, "--time", "0.25", "--lights", "12", "-q",
                               "-o", f"{out}/cli.exr", "--vertex-out", f"{out}/cli.rslv")
        assert status == 0, text
        status, text = run_rsl("truth", cls.scene_file, "--time", "0.25", "-q",
                               "-o", f"{out}/truth.exr", "--vertex-out", f"{out}/truth.rslv")
        assert status == 0, text
        cls.renderer = rsl.Renderer(rsl.Scene.load(cls.scene_file), lights=12)
        cls.renderer.set_time(0.25)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.folder)

    def test_frame_and_image_are_rsl_renders(self):
        colors = self.renderer.shade()
        cli, info = rsl.read_vertex_colors(f"{self.folder}/cli.rslv")
        self.assertEqual(colors.dtype, np.float32)
        self.assertEqual(colors.shape, cli.shape)
        self.assertEqual(info["part_names"], self.renderer.part_names)
        self.assertEqual(info["part_offsets"], self.renderer.part_offsets)
        self.assertGreater(colors.max(), 0.01)  # a lit frame, not two black ones
        np.testing.assert_array_equal(colors, cli)
        # The renderer's image (per-pixel shadows and highlights) is rsl render's;
        # form_image draws the colours alone, as a renderer with neither pass.
        image = self.renderer.render_image()
        self.assertEqual(image.shape, (72, 96, 4))
        np.testing.assert_array_equal(image, rsl.read_image(f"{self.folder}/cli.exr"))
        plain = rsl.Renderer(rsl.Scene.load(self.scene_file), lights=12, pixel_shadows="off", pixel_highlights=False)
        plain.set_time(0.25)
        np.testing.assert_array_equal(self.renderer.form_image(colors), plain.render_image())
        # The RSL paper's sum, as rsl render --no-exact-diffuse-light.
        status, text = run_rsl("render", self.scene_file, "--time", "0.25", "--lights", "12", "-q",
                               "--no-exact-diffuse-light", "-o", f"{self.folder}/paper.exr",
                               "--vertex-out", f"{self.folder}/paper.rslv")
        self.assertEqual(status, 0, text)
        paper = rsl.Renderer(rsl.Scene.load(self.scene_file), lights=12, exact_diffuse_light=False)
        paper.set_time(0.25)
        paper_colors = paper.shade()
        np.testing.assert_array_equal(paper_colors, rsl.read_vertex_colors(f"{self.folder}/paper.rslv")[0])
        self.assertGreater(rsl.compare(paper_colors, colors)["relative_l2"], 1e-3)

    def test_rays_backend_is_rsl_render_backend_rays(self):
        out = self.folder
        status, text = run_rsl("render", self.scene_file, "--backend", "rays", "--ray-samples", "2", "--time", "0.25",
                               "--lights", "12", "-q", "-o", f"{out}/rays.exr", "--vertex-out", f"{out}/rays.rslv")
        self.assertEqual(status, 0, text)
        rays = rsl.Renderer(rsl.Scene.load(self.scene_file), lights=12, backend="rays", ray_samples=2)
        self.assertEqual(rays.backend, "rays")
        self.assertEqual(rays.setup["fields_loaded"] + rays.setup["fields_baked"], 0)
        rays.set_time(0.25)
        colors = rays.shade()
        cli, info = rsl.read_vertex_colors(f"{out}/rays.rslv")
        self.assertEqual(info["producer"], "rsl-rays")
        self.assertGreater(colors.max(), 0.01)
        np.testing.assert_array_equal(colors, cli)
        self.assertIn("rays", rsl.build_info()["backends"])
        with self.assertRaisesRegex(rsl.Error, r"ray_samples 2: the cpu backend traces no rays \(backends that do: rays\)"):
            rsl.Renderer(rsl.Scene.load(self.scene_file), lights=12, ray_samples=2)

    def test_truth_and_errors_are_rsl_truths_and_compares(self):
        colors, truth = self.renderer.shade(), self.renderer.truth()
        cli_truth, info = rsl.read_vertex_colors(f"{self.folder}/truth.rslv")
        self.assertEqual(info["producer"], "truth")
        np.testing.assert_array_equal(truth, cli_truth)
        status, text = run_rsl("compare", f"{self.folder}/cli.rslv", f"{self.folder}/truth.rslv")
        self.assertEqual(status, 0, text)
        error = rsl.compare(colors, truth)
        self.assertAlmostEqual(error["relative_l2"] / number_after(text, "relative L2:"), 1.0, places=5)
        # The definition, by numpy: ‖A − B‖₂ / ‖B‖₂ over every RGB value.
        by_numpy = np.linalg.norm((colors - truth).astype(np.float64)) / np.linalg.norm(truth.astype(np.float64))
        self.assertAlmostEqual(error["relative_l2"] / by_numpy, 1.0, places=5)
        self.assertTrue(0.001 < error["relative_l2"] < 0.25, error)
        by_part = self.renderer.compare(colors, truth)
        parts = by_part["parts"]
        self.assertEqual(sorted(parts), ["floor", "orb"])
        self.assertAlmostEqual(parts["orb"] / number_after(text, "part orb: relative L2"), 1.0, places=5)
        # The objects (all but the floor: the orb) and the worst part, as rsl compare prints them.
        self.assertAlmostEqual(by_part["objects"] / number_after(text, "objects: relative L2"), 1.0, places=5)
        self.assertEqual(by_part["worst_part"], "orb")
        self.assertAlmostEqual(by_part["worst"], parts["orb"], places=9)
        self.assertNotIn("objects", error)  # bare arrays have no parts
        # With the orb as a receiver too, no part is an object.
        self.assertNotIn("objects", self.renderer.compare(colors, truth, receivers=["orb", "floor"]))
        status, text = run_rsl("compare", f"{self.folder}/cli.exr", f"{self.folder}/truth.exr")
        image_error = rsl.compare_images(self.renderer.render_image(), self.renderer.form_image(truth))
        self.assertAlmostEqual(image_error["relative_l2"] / number_after(text, "relative L2:"), 1.0, places=5)
        self.assertAlmostEqual(image_error["relative_h1"] / number_after(text, "relative H1:"), 1.0, places=5)

    def test_fit_is_rsl_fits_and_drives_the_renderer(self):
        status, text = run_rsl("fit", SUNSKY, "--lights", "10", "--resolution", "12", "-o", f"{self.folder}/fit.json")
        self.assertEqual(status, 0, text)
        with open(f"{self.folder}/fit.json") as f:
            lights = json.load(f)["lights"]
        fit = rsl.fit_environment(SUNSKY, 10, resolution=12)
        self.assertEqual(fit["centers"].shape, (10, 3))
        np.testing.assert_array_equal(fit["centers"], np.array([l["center"] for l in lights], dtype=np.float32))
        np.testing.assert_array_equal(fit["half_diagonals"], np.array([l["half_diagonal"] for l in lights], dtype=np.float32))
        np.testing.assert_array_equal(fit["radiance"], np.array([l["radiance"] for l in lights], dtype=np.float32))
        self.assertAlmostEqual(fit["relative_l2"], number_after(text, "reconstructed map:"), places=4)
        # Its lights in a renderer fitted with 12 shade as a renderer fitted with 10.
        ten = rsl.Renderer(rsl.Scene.load(self.scene_file), lights=10)
        twelve = rsl.Renderer(rsl.Scene.load(self.scene_file), lights=12)
        self.assertEqual(twelve.environment_lights["centers"].shape, (12, 3))
        twelve.set_environment_lights(fit["centers"], fit["half_diagonals"], fit["radiance"])
        for r in (ten, twelve):
            r.set_time(0.25)
        np.testing.assert_array_equal(twelve.shade(), ten.shade())
        np.testing.assert_array_equal(twelve.environment_lights["centers"], fit["centers"])

    def test_poses_from_python_equal_a_scene_file(self):
        moved = write_scene(self.folder, "moved.json",
                            orb_transform={"translation": [0.25, 0.05, -0.1], "rotation_axis_angle": [0, 1, 0, 90]},
                            rotation={"axis": [0, 1, 0], "degrees": 75, "degrees_per_second": 0})
        expected = rsl.Renderer(rsl.Scene.load(moved), lights=12)
        expected.set_time(0.5)
        r = rsl.Renderer(rsl.Scene.load(self.scene_file), lights=12)
        r.set_time(0.5)
        before = r.shade()
        half = np.sqrt(0.5, dtype=np.float32)
        r.set_part_pose("orb", translation=(0.25, 0.05, -0.1), rotation=(half, 0, half, 0))
        r.set_environment_rotation((0, 1, 0), 75)
        after = r.shade()
        self.assertGreater(rsl.compare(before, after)["relative_l2"], 0.05)
        np.testing.assert_allclose(after, expected.shade(), rtol=1e-5, atol=1e-6)
        np.testing.assert_allclose(r.truth(), expected.truth(), rtol=1e-5, atol=1e-6)
        # The same pose as a 4×4 matrix (numpy's row-major M @ [x, y, z, 1]).
        matrix = np.array([[0, 0, 1, 0.25], [0, 1, 0, 0.05], [-1, 0, 0, -0.1], [0, 0, 0, 1]], dtype=np.float32)
        r.set_part_pose(0, matrix=matrix)
        np.testing.assert_allclose(r.part_transform("orb"), matrix, atol=1e-6)
        np.testing.assert_allclose(r.shade(), after, rtol=1e-5, atol=1e-6)

    def test_a_textured_materials_factors_are_edited_as_any_material(self):
        """The generated walker's material has a metallic-roughness texture; its roughness factor scales it."""
        scene = {"name": "walker", "gltf": os.path.join(GENERATED, "walker.glb"),
                 "environment": {"file": SUNSKY, "resolution": 12},
                 "camera": {"position": [0.5, 1.6, 3.0], "target": [1, 0.8, 0], "up": [0, 1, 0], "fov_degrees": 40,
                            "width": 96, "height": 72},
                 "subdivision": False,
                 "precompute": {"svdf": {"resolution": 8, "clusters": 16, "vectors": 4, "supersampling": 1},
                                "ovdf": {"shells": 4, "inner_radius": 0.4, "outer_radius": 6.0,
                                         "cube_resolution": 6, "vdt_resolution": 8, "vectors": 4}}}
        path = os.path.join(self.folder, "walker.json")
        with open(path, "w") as f:
            json.dump(scene, f)
        r = rsl.Renderer(rsl.Scene.load(path), lights=12)
        before = r.shade()
        r.set_material_parameter("walker", "roughness", 0.4)
        edited = r.shade()
        self.assertGreater(rsl.compare(edited, before)["relative_l2"], 0.01)
        r.set_material_parameter("walker", "roughness", 1.0)
        np.testing.assert_array_equal(r.shade(), before)  # the edit undone: the frame it was
        with self.assertRaisesRegex(rsl.Error, "roughness"):
            r.set_material_parameter("walker", "roughness", 1.5)

    def test_long_calls_release_the_gil(self):
        # The main thread counts while a worker runs the truth (T seconds).
        # Holding the GIL, the call would let it count for a thread switch
        # (5 ms) at most; released, for all of T, if at a third of its speed
        # (the truth's threads take the cores).
        r = self.renderer
        start = time.perf_counter()
        r.truth(subdivision=4)
        seconds = time.perf_counter() - start
        idle = threading.Event()
        waiting = threading.Thread(target=idle.wait)
        waiting.start()
        start = time.perf_counter()
        for _ in range(200000):
            waiting.is_alive()
        rate = 200000 / (time.perf_counter() - start)  # loop turns per second
        idle.set()
        result, count = {}, 0
        worker = threading.Thread(target=lambda: result.setdefault("truth", r.truth(subdivision=4)))
        worker.start()
        while worker.is_alive():
            count += 1
        worker.join()
        self.assertEqual(result["truth"].shape, (r.part_offsets[-1], 3))
        self.assertGreater(seconds, 0.1)
        self.assertGreater(count, 0.05 * rate * seconds, f"{count} turns in a {seconds:.2f} s call at {rate:.0f}/s")

    def test_progress_reaches_a_callable(self):
        heard = {}

        def progress(what, fraction):
            heard.setdefault(what, []).append(fraction)

        baked = rsl.bake_fields(rsl.Scene.load(self.scene_file), f"{self.folder}/cache", progress=progress)
        self.assertEqual((baked["fields_baked"], baked["fields_loaded"]), (4, 0))
        r = rsl.Renderer(rsl.Scene.load(self.scene_file), lights=12, field_cache=f"{self.folder}/cache",
                         progress=progress)
        self.assertEqual((r.setup["fields_baked"], r.setup["fields_loaded"]), (0, 4))
        self.assertIn("fit", heard)
        bakes = [what for what in heard if what.startswith(("SVDF ", "OVDF "))]
        self.assertEqual(len(bakes), 4, heard.keys())
        r.truth(progress=progress)
        for what, fractions in heard.items():
            self.assertTrue(all(0.0 <= f <= 1.0 for f in fractions), what)
            self.assertEqual(fractions[-1], 1.0, what)
        self.assertIn("truth", heard)

        def failing(what, fraction):
            raise ValueError("stop: " + what)

        with self.assertRaisesRegex(ValueError, "stop: "):
            rsl.Renderer(rsl.Scene.load(self.scene_file), lights=12, field_cache=f"{self.folder}/cache2",
                         progress=failing)

    def test_errors_carry_the_programs_message(self):
        missing = f"{self.folder}/missing.json"
        status, text = run_rsl("truth", missing, "-q", "-o", f"{self.folder}/x.exr")
        self.assertEqual(status, 1)
        with self.assertRaises(rsl.Error) as caught:
            rsl.Scene.load(missing)
        self.assertEqual("rsl: error: " + str(caught.exception) + "\n", text)
        self.assertTrue(issubclass(rsl.Error, RuntimeError))
        with self.assertRaisesRegex(rsl.Error, "no part 'ball'"):
            self.renderer.set_part_pose("ball")
        with self.assertRaisesRegex(rsl.Error, r"expected an array of shape \(N, 3\)"):
            rsl.compare(np.zeros((4, 2)), np.zeros((4, 2)))
        with self.assertRaisesRegex(rsl.Error, "unknown renderer backend 'vulkan'"):
            rsl.Renderer(rsl.Scene.load(self.scene_file), backend="vulkan")

    def test_scene_built_from_arrays(self):
        scene = rsl.Scene("quad")
        scene.add_material("grey", "lambert", albedo=(0.5, 0.5, 0.5))
        positions = np.array([[-1, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1]], dtype=np.float32)
        scene.add_part("quad", positions, np.array([[0, 2, 1], [0, 3, 2]]), "grey")
        scene.add_sphere_light((0, 1, 0), radius=0.1, power=(10, 10, 10))
        scene.set_camera((0, 2, 2), (0, 0, 0), width=32, height=24)
        scene.set_precompute(svdf_resolution=8, svdf_clusters=4, svdf_vectors=2, svdf_supersampling=1)
        self.assertEqual(scene.part_vertex_counts, [4])
        r = rsl.Renderer(scene)
        colors = r.shade()
        self.assertTrue((colors > 0).all())
        # Corners the mirror x → −x swaps alike, all within 1% (tests/api/api_scene_test.cpp says why).
        np.testing.assert_allclose(colors[[1, 0, 3, 2]], colors, rtol=1e-5)
        np.testing.assert_allclose(colors, np.broadcast_to(colors[0], colors.shape), rtol=0.01)
        self.assertLess(rsl.compare(colors, r.truth())["relative_l2"], 0.02)
        self.assertEqual(r.render_image().shape, (24, 32, 4))

    def test_emissive_parameter_adds_exactly_its_radiance(self):
        r = rsl.Renderer(rsl.Scene.load(self.scene_file), lights=12)
        r.set_time(0.25)
        before = r.shade()
        r.set_material_parameter("floor", "emissive", (0.5, 0.25, 2.0))
        after = r.shade()
        floor = slice(r.part_offsets[1], r.part_offsets[2])
        np.testing.assert_allclose(after[floor] - before[floor], np.broadcast_to([0.5, 0.25, 2.0], after[floor].shape),
                                   rtol=1e-6, atol=1e-6 * float(after[floor].max()))
        np.testing.assert_array_equal(after[: r.part_offsets[1]], before[: r.part_offsets[1]])  # the orb: unchanged
        for value in (-1.0, (1e30, 0, 0)):
            with self.assertRaisesRegex(rsl.Error, re.escape("material 'floor': parameter 'emissive'")):
                r.set_material_parameter("floor", "emissive", value)
        with self.assertRaisesRegex(rsl.Error, "emissive"):
            r.set_material_parameter("floor", "emissive", float("nan"))
        np.testing.assert_array_equal(r.shade(), after)  # a refused edit changes nothing

    def test_build_info(self):
        info = rsl.build_info()
        self.assertEqual(info["version"], rsl.__version__)
        status, text = run_rsl("--version")
        self.assertEqual(status, 0)
        self.assertTrue(text.startswith(f"rsl {info['version']}\ncommit: {info['commit']}\n"), text)

    def test_calls_from_several_threads_take_turns(self):
        # Issue 56: with the GIL released, a set_time in one thread landed in the middle of another's shade.
        r = rsl.Renderer(rsl.Scene.load(self.scene_file), lights=12)
        frames = []
        for t in (0.25, 0.5):
            r.set_time(t)
            frames.append(r.shade())
        self.assertFalse(np.array_equal(frames[0], frames[1]))  # the scene moves between the two
        seen, errors = [], []

        def work(t):
            try:
                for _ in range(6):
                    r.set_time(t)
                    seen.append(r.shade())
                    r.render_image(width=24, height=18)
            except Exception as e:  # reported below, not lost in the thread
                errors.append(e)

        threads = [threading.Thread(target=work, args=(t,)) for t in (0.25, 0.5, 0.25, 0.5)]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        self.assertEqual(errors, [])
        self.assertEqual(len(seen), 24)
        for colors in seen:  # each shade saw one pose whole: one of the two frames, never a mixture
            self.assertTrue(any(np.array_equal(colors, frame) for frame in frames))

    def test_sizes_and_lights_follow_the_programs_limits(self):
        r = rsl.Renderer(rsl.Scene.load(self.scene_file), lights=12)
        with self.assertRaisesRegex(rsl.Error, re.escape("image size 100000×100000: expected 1 to 16384 pixels a side")):
            r.render_image(width=100000, height=100000)  # was a MemoryError after minutes
        with self.assertRaisesRegex(rsl.Error, re.escape("samples 1000: expected 1 to 16")):
            r.form_image(r.shade(), width=8, height=8, samples=1000)
        with self.assertRaisesRegex(rsl.Error, re.escape("camera size 1000000×1000000: expected 1 to 16384")):
            r.set_camera([0, 1, 4], [0, 0, 0], width=10**6, height=10**6)
        one = np.zeros((1, 3), dtype=np.float32)
        with self.assertRaisesRegex(rsl.Error, re.escape("local light 0.power: 3e+38 W is past the limit")):
            r.set_sphere_lights(one, np.array([0.05], dtype=np.float32), np.full((1, 3), 3e38, dtype=np.float32))
        with self.assertRaisesRegex(rsl.Error, re.escape("local light 0: radiance power / (4π² radius²)")):
            r.set_sphere_lights(one, np.array([1e-9], dtype=np.float32), np.full((1, 3), 100, dtype=np.float32))

    def test_arguments_pybind_cannot_cast_are_rsl_errors_naming_them(self):
        r = rsl.Renderer(rsl.Scene.load(self.scene_file), lights=12)
        for part in (10**12, 2**70, -1):  # pybind's "Unable to cast Python instance to C++ type" for the first two
            with self.assertRaisesRegex(rsl.Error, re.escape(f"part {part}: scene 'python-test' has 2 parts")):
                r.set_part_pose(part)
        with self.assertRaisesRegex(rsl.Error, re.escape("part: expected an index or a name, got float")):
            r.part_transform(1.5)
        for value, got in (("red", "str"), (["a", 1, 2], "list"), (10**400, "int"), (None, "NoneType")):
            with self.assertRaisesRegex(rsl.Error, re.escape(f"set_material_parameter 'albedo': expected a number "
                                                             f"or 3 numbers, got {got}")):
                r.set_material_parameter("floor", "albedo", value)
        for limit, shown in ((-1, "-1"), (2**70, str(2**70)), (1.5, "float")):
            with self.assertRaisesRegex(rsl.Error, re.escape(f"set_memory_limit {shown}: expected a number of bytes")):
                rsl.set_memory_limit(limit)
        with self.assertRaisesRegex(rsl.Error, re.escape("set_precompute svdf_resolution 1000000000000: expected a "
                                                         "whole number from 0 to 2147483647")):
            rsl.Scene.load(self.scene_file).set_precompute(svdf_resolution=10**12)
        # A scale whose determinant is Inf or 0 in float: refused here, not later by the ray scene, unnamed.
        before = r.part_transform("orb")
        for scale in ((1e20, 1e20, 1e20), (1e-30, 1, 1)):
            with self.assertRaisesRegex(rsl.Error, re.escape("part 'orb' pose scale: ") + ".*makes a singular transform"):
                r.set_part_pose("orb", scale=scale)
        np.testing.assert_array_equal(r.part_transform("orb"), before)  # unchanged

    def test_writes_never_replace_the_scenes_inputs(self):
        folder = tempfile.mkdtemp(prefix="rsl_py_inputs_")
        self.addCleanup(shutil.rmtree, folder, ignore_errors=True)
        scene_file = write_scene(folder, "scene.json")
        mesh = os.path.join(folder, "floor.obj")
        with open(mesh, "rb") as f:
            before = f.read()
        r = rsl.Renderer(rsl.Scene.load(scene_file), lights=4)
        self.assertIn(os.path.realpath(mesh), [os.path.realpath(p) for p in r.input_files])
        # By another spelling of the same file: the check compares files, not strings.
        spelled = os.path.join(folder, ".", "floor.obj")
        with self.assertRaisesRegex(rsl.Error, re.escape(spelled + ": this output is the input ") + ".*floor.obj"):
            r.write_vertex_colors(spelled, r.shade())
        with open(mesh, "rb") as f:
            self.assertEqual(f.read(), before)  # was replaced by the colours
        # The free function knows a scene's inputs only when given them.
        environment = os.path.join(folder, "sky.exr")
        shutil.copy(SUNSKY, environment)
        with open(environment, "rb") as f:
            sky = f.read()
        built = rsl.Scene("built")
        built.set_environment(environment, 8)
        with self.assertRaisesRegex(rsl.Error, re.escape(environment + ": this output is the input " + environment)):
            rsl.write_image(environment, np.ones((2, 3, 4), dtype=np.float32), inputs=built.input_files)
        with open(environment, "rb") as f:
            self.assertEqual(f.read(), sky)
        self.assertFalse(os.path.exists(os.path.join(folder, "sky.png")))

    def test_the_memory_refusal_names_pythons_way_out(self):
        limit = rsl.memory_limit()
        self.addCleanup(rsl.set_memory_limit, limit)
        r = rsl.Renderer(rsl.Scene.load(self.scene_file), lights=12)
        rsl.set_memory_limit("100M")
        # 16384² pixels at 32 bytes: 8.6 GB, refused before the image is allocated.
        with self.assertRaisesRegex(rsl.Error, re.escape("16384×16384 image), over rsl's limit of 105 MB") +
                                    ".*raise the limit with rsl.set_memory_limit or RSL_MEMORY_LIMIT"):
            r.render_image(width=16384, height=16384)
        rsl.set_memory_limit("20M")  # below even the scene's own estimate
        with self.assertRaisesRegex(rsl.Error, re.escape(self.scene_file + ": needs about ") +
                                    ".*raise the limit with rsl.set_memory_limit or RSL_MEMORY_LIMIT"):
            rsl.Renderer(rsl.Scene.load(self.scene_file), lights=12)
        with self.assertRaises(rsl.Error) as refused:
            rsl.Renderer(rsl.Scene.load(self.scene_file), lights=12)
        self.assertNotIn("--memory-limit", str(refused.exception))  # the program's flag, not Python's

    def test_non_finite_values_are_refused_before_anything_is_formed_or_written(self):
        colors = self.renderer.shade().copy()
        colors[3, 1] = np.nan
        with self.assertRaisesRegex(ValueError, re.escape("form_image: colors[3, 1] is NaN")):
            self.renderer.form_image(colors)
        rslv = os.path.join(self.folder, "nan.rslv")
        with self.assertRaisesRegex(ValueError, re.escape(rslv + ": colors[3, 1] is NaN") + ".*nothing written"):
            self.renderer.write_vertex_colors(rslv, colors)
        self.assertFalse(os.path.exists(rslv))
        image = np.ones((2, 3, 4), dtype=np.float32)
        image[1, 2, 0] = -np.inf
        exr = os.path.join(self.folder, "inf.exr")
        with self.assertRaisesRegex(ValueError, re.escape(exr + ": image[1, 2, 0] is infinite")):
            rsl.write_image(exr, image)
        self.assertFalse(os.path.exists(exr))
        self.assertFalse(os.path.exists(os.path.join(self.folder, "inf.png")))


class HostileInputTest(unittest.TestCase):
    """Issue 43: nothing hangs, nothing lies: special files and out-of-range values raise rsl.Error at once."""

    def setUp(self):
        self.folder = tempfile.mkdtemp(prefix="rsl_py_hostile_")
        self.addCleanup(shutil.rmtree, self.folder, ignore_errors=True)

    def test_a_fifo_scene_is_refused_at_once(self):
        fifo = os.path.join(self.folder, "ff.json")
        os.mkfifo(fifo)
        def release():  # a blocked reader (the defect) then reads nothing, and the test fails instead of hanging
            time.sleep(5)
            try:
                os.close(os.open(fifo, os.O_WRONLY | os.O_NONBLOCK))
            except OSError:
                pass
        threading.Thread(target=release, daemon=True).start()
        start = time.monotonic()
        with self.assertRaisesRegex(rsl.Error, re.escape(fifo + ": is a FIFO (named pipe), not a regular file")):
            rsl.Scene.load(fifo)
        self.assertLess(time.monotonic() - start, 3)

    def quad(self):
        scene = rsl.Scene("quad")
        scene.add_material("grey", "lambert", albedo=(0.5, 0.5, 0.5))
        positions = np.array([[-1, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1]], dtype=np.float32)
        scene.add_part("quad", positions, np.array([[0, 2, 1], [0, 3, 2]]), "grey")
        scene.set_precompute(svdf_resolution=8, svdf_clusters=4, svdf_vectors=2, svdf_supersampling=1)
        return scene

    def test_precompute_settings_follow_the_scene_files_rules(self):
        scene = self.quad()
        with self.assertRaisesRegex(rsl.Error, "precompute: svdf_resolution must be an integer from 2 to 256, got 1"):
            scene.set_precompute(svdf_resolution=1)
        with self.assertRaisesRegex(rsl.Error, "precompute: ovdf_cube_resolution must be even, got 5"):
            scene.set_precompute(ovdf_cube_resolution=5)

    def test_field_cache_must_be_a_path(self):
        scene = self.quad()
        cwd = os.getcwd()
        os.chdir(self.folder)
        self.addCleanup(os.chdir, cwd)
        with self.assertRaisesRegex(rsl.Error, "field_cache: expected a path \\(str or os.PathLike\\), got int"):
            rsl.bake_fields(scene, field_cache=123)
        with self.assertRaisesRegex(rsl.Error, "field_cache: expected a path"):
            rsl.Renderer(scene, field_cache=123)
        self.assertFalse(os.path.exists(os.path.join(self.folder, "123")))

    def test_compare_refuses_nan(self):
        good = np.ones((4, 3), dtype=np.float32)
        bad = good.copy()
        bad[2, 1] = np.nan
        with self.assertRaisesRegex(rsl.Error, "compare result: vertex 2 holds nan: a comparison needs finite values"):
            rsl.compare(bad, good)
        with self.assertRaisesRegex(rsl.Error, "compare reference: vertex 2 holds nan"):
            rsl.compare(good, bad)
        image = np.ones((2, 3, 4), dtype=np.float32)
        broken = image.copy()
        broken[1, 2, 0] = np.inf
        with self.assertRaisesRegex(rsl.Error, "compare result: pixel 5 holds inf"):
            rsl.compare_images(broken, image)


if __name__ == "__main__":
    unittest.main(verbosity=2)
