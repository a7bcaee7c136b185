"""The Python API: parameters, steps and progress, layers as arrays, bad input, threads."""

import threading
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import hibi


def test_defaults_are_the_papers_and_presets_apply():
    assert hibi.Mud().params["young_modulus"] == 1.0e6
    assert hibi.Mud().params["topology"] == "hexagonal"
    assert hibi.Glass().params["width"] == 640.0
    assert hibi.Mud("fig6c").params["shear_modulus"] == 1.0e5
    assert hibi.Mud("fig6c", shear_modulus=3.0e4).params["shear_modulus"] == 3.0e4
    assert set(hibi.presets()) == {"mud", "glass", "skin"}
    assert "fig19a" in hibi.Skin.presets()


def test_steps_report_progress_and_end_where_run_ends():
    stepped = hibi.Glass(width=200, height=200, seed=3)
    seen = []
    while True:
        p = stepped.step(20_000)
        seen.append(p.work)
        if p.finished:
            break
    assert len(seen) > 1 and seen == sorted(seen)
    ran = hibi.Glass(width=200, height=200, seed=3)
    ran.run()
    assert np.array_equal(stepped.render("mask"), ran.render("mask"))
    calls = []
    mud = hibi.Mud(columns=24, rows=24)
    last = mud.run(callback=calls.append, budget=200_000)
    assert last.finished and len(calls) > 1 and calls[-1].finished
    assert not calls[0].finished and calls[0].shrink <= calls[-1].shrink


def test_layers_are_arrays_of_the_right_shape_and_type():
    mud = hibi.Mud(columns=24, rows=24)
    mud.run()
    layers = mud.render(["mask", "height", "height16", "normal", "normal_rgb8", "time", "preview"], width=96)
    w, h = 96, round(96 * mud.extent[1] / mud.extent[0])
    expected = {
        "mask": ((h, w), np.uint8),
        "height": ((h, w), np.float32),
        "height16": ((h, w), np.uint16),
        "normal": ((h, w, 3), np.float32),
        "normal_rgb8": ((h, w, 3), np.uint8),
        "time": ((h, w), np.float32),
        "preview": ((h, w, 4), np.uint8),
    }
    assert list(layers) == list(expected)
    for name, (shape, dtype) in expected.items():
        a = layers[name]
        assert a.shape == shape and a.dtype == dtype, name
        assert a.flags.c_contiguous and a.flags.writeable
        # The array took over the Rust buffer: its base is that buffer, not another array.
        assert not isinstance(a.base, np.ndarray), name
    assert layers["mask"].max() == 255 and layers["mask"].min() == 0
    assert np.isinf(layers["time"]).any() and np.isfinite(layers["time"]).any()


def test_networks_cells_and_fragments_are_points_with_offsets():
    mud = hibi.Mud(columns=32, rows=32)
    mud.run()
    net = mud.network()
    assert net["offsets"][0] == 0 and net["offsets"][-1] == len(net["points"])
    assert len(net["from"]) == len(net["offsets"]) - 1
    cells = mud.cells()
    assert cells["points"].shape[1] == 2 and cells["offsets"][-1] == len(cells["points"])
    outer = cells["hole_of"] == 0xFFFFFFFF
    assert (cells["area"][outer] > 0).all()
    glass = hibi.Glass(width=200, height=200, seed=5)
    glass.run()
    frags = glass.fragments()
    # The fragments tile the plate: their outer areas less their holes sum to its area.
    assert abs(frags["area"].sum() - 200 * 200) < 1.0
    skin = hibi.Skin(width=80, height=80)
    skin.run()
    c = skin.cells()
    assert c["offsets"][-1] == len(c["points"]) == len(c["fixed"])
    assert np.array_equal(c["points"], c["fixed"] / 2.0 ** c["fixed_point_bits"])


@pytest.mark.parametrize(
    "make, field",
    [
        (lambda: hibi.Mud(columns=1), "columns"),
        (lambda: hibi.Mud(rows=5), "rows"),
        (lambda: hibi.Mud(shear_modulus=-1.0), "shear_modulus"),
        (lambda: hibi.Mud(break_stretch_mean=float("nan")), "break_stretch_mean"),
        (lambda: hibi.Mud(topology="hex"), "topology"),
        (lambda: hibi.Mud("fig99"), "preset"),
        (lambda: hibi.Glass(impact=(700.0, 10.0)), "impact"),
        (lambda: hibi.Glass(turn_limit=4.0), "turn_limit"),
        (lambda: hibi.Glass(spread_ratio=1.0), "spread_ratio"),
        (lambda: hibi.Glass(width=0.5), "width"),
        (lambda: hibi.Skin(levels=7), "levels"),
        (lambda: hibi.Skin(jitter_ratio=2.0), "jitter_ratio"),
        (lambda: hibi.Skin(level=[{"spacing": 0.5}]), "spacing"),
        (lambda: hibi.Skin(level=[{"profile": [(0, 1), (1, 1)]}]), "profile"),
        (lambda: hibi.Skin(layout="hexagonal"), "layout"),
    ],
)
def test_bad_parameters_raise_value_error_naming_the_field(make, field):
    with pytest.raises(ValueError, match=field):
        make()


def test_wrong_types_and_unknown_keywords_raise_type_error():
    with pytest.raises(TypeError, match="columns"):
        hibi.Mud(columns="many")
    with pytest.raises(TypeError, match="colums"):
        hibi.Mud(colums=8)
    with pytest.raises(TypeError, match="impact"):
        hibi.Glass(impact=3)


def test_bad_render_input_names_the_field_and_leaves_the_model_as_it_was():
    mud = hibi.Mud(columns=16, rows=16)
    mud.run()
    before = mud.render("mask", width=64)
    for kwargs, field in [
        (dict(layers="cell"), "cell"),
        (dict(layers="bogus"), "bogus"),
        (dict(width_scale=-1.0), "width_scale"),
        (dict(min_width=float("inf")), "min_width"),
        (dict(until=float("nan")), "until"),
        (dict(width=0), "width"),
    ]:
        with pytest.raises(ValueError, match=field):
            mud.render(**kwargs)
    assert np.array_equal(mud.render("mask", width=64), before)
    glass = hibi.Glass(width=120, height=120)
    glass.run()
    with pytest.raises(ValueError, match="line_width"):
        glass.render(line_width=0.0)
    with pytest.raises(ValueError, match="time"):
        hibi.Skin(width=40, height=40).render("time")
    skin = hibi.Skin(width=40, height=40)
    skin.run()
    with pytest.raises(ValueError, match="ambient"):
        skin.render("preview", ambient=2.0)
    with pytest.raises(ValueError, match="cell_level"):
        skin.render("cell", cell_level=3)


def test_a_refused_impact_changes_nothing():
    glass = hibi.Glass(width=150, height=150, seed=2)
    glass.run()
    cracks = glass.cracks()
    with pytest.raises(ValueError, match="impact"):
        glass.impact((-1.0, 20.0))
    after = glass.cracks()
    assert all(np.array_equal(cracks[k], after[k]) for k in cracks)
    counts = glass.impact((30.0, 30.0))
    assert counts["radial"] > 0
    glass.run()
    assert len(glass.cracks()["end"]) > len(cracks["end"])


def glass_mask(seed):
    g = hibi.Glass(width=320, height=320, seed=seed)
    g.run()
    return g.render("mask")


def test_threads_give_the_same_arrays_as_one_thread():
    seeds = [1, 2, 3, 4]
    alone = [glass_mask(s) for s in seeds]
    with ThreadPoolExecutor(4) as pool:
        together = list(pool.map(glass_mask, seeds))
    assert all(np.array_equal(a, b) for a, b in zip(alone, together))
    assert not np.array_equal(alone[0], alone[1])


def test_a_render_on_several_threads_gives_the_same_arrays():
    # Each band of rows is drawn by its own thread; the core draws every pixel of a band as
    # the whole raster has it.
    mud = hibi.Mud(columns=24, rows=24)
    mud.run()
    glass = hibi.Glass(width=120, height=90, impact=(60, 45))
    glass.run()
    skin = hibi.Skin(width=64, height=48)
    skin.run()
    cases = [
        (mud, ["mask", "height", "normal", "time", "preview"], {"width": 61, "height": 37}),
        (glass, ["mask", "height16", "normal_rgb8", "time", "preview"], {}),
        (skin, ["mask", "height", "normal", "cell", "preview"], {}),
    ]
    for model, layers, view in cases:
        one = model.render(layers, **view)
        for threads in (2, 3, 7):
            many = model.render(layers, threads=threads, **view)
            for name in layers:
                assert np.array_equal(one[name], many[name], equal_nan=True), (type(model).__name__, name, threads)
    with pytest.raises(ValueError, match="threads"):
        glass.render("mask", threads=0)


def test_the_gil_is_released_while_a_model_runs():
    # While another thread is inside run(), this thread keeps running Python: if run() held
    # the GIL, this loop would be stopped for the whole run.
    mud = hibi.Mud(columns=160, rows=160)
    worker = threading.Thread(target=mud.run)
    ticks = 0
    start = time.perf_counter()
    worker.start()
    while worker.is_alive():
        ticks += 1
    elapsed = time.perf_counter() - start
    worker.join()
    assert mud.progress.finished
    assert elapsed > 0.05, "the run is too short to tell"
    assert ticks > 10_000, f"{ticks} loop turns in {elapsed:.2f} s: the GIL was held"


def test_png_bytes_are_fixed_by_the_pixels():
    a = np.arange(64 * 48, dtype=np.uint16).reshape(48, 64)
    png = hibi.encode_png(a)
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and png == hibi.encode_png(a.copy())
    assert hibi.encode_png(np.zeros((4, 5, 3), np.uint8)) != hibi.encode_png(np.zeros((4, 5, 4), np.uint8))
    with pytest.raises(ValueError, match="shape"):
        hibi.encode_png(np.zeros((4, 5, 2), np.uint8))


def test_the_stubs_name_every_public_attribute():
    import pathlib

    stub = (pathlib.Path(hibi.__file__).parent / "_hibi.pyi").read_text()
    for cls in (hibi.Mud, hibi.Glass, hibi.Skin, hibi.MudProgress, hibi.GlassProgress, hibi.SkinProgress):
        assert f"class {cls.__name__}:" in stub
        for name in dir(cls):
            if not name.startswith("_"):
                assert f"def {name}(" in stub or f"    {name}:" in stub, f"{cls.__name__}.{name}"
    for name in ("encode_png", "presets"):
        assert f"def {name}(" in stub
