"""The golden scenes the Python API reaches hash to the values Rust lists.

The hashes are read from targets/scenes/src/lib.rs (GOLDENS), the list tests/goldens.rs and
targets/run check natively; each scene is rebuilt here through hibi's Python API and hashed
as the Rust scene hashes it (FNV-1a, 64-bit, over the same bytes in the same order).
"""

import pathlib
import re

import numpy as np
import pytest

import hibi

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENES = ROOT / "targets" / "scenes" / "src" / "lib.rs"


def goldens():
    text = SCENES.read_text()
    table = text[text.index("pub const GOLDENS") :]
    table = table[: table.index("];")]
    return {name: int(value) for name, value in re.findall(r'\("([^"]+)",\s*(\d+)\)', table)}


GOLDENS = goldens()

FNV_OFFSET = 0xCBF29CE484222325
FNV_PRIME = 0x100000001B3
MASK64 = (1 << 64) - 1


def fnv(data, h=FNV_OFFSET):
    """FNV-1a 64 over bytes (NumPy arrays are taken as their little-endian bytes)."""
    if isinstance(data, np.ndarray):
        data = data.tobytes()
    for b in data:
        h = ((h ^ b) * FNV_PRIME) & MASK64
    return h


def le(*arrays):
    """The little-endian bytes of arrays laid out as columns, row after row."""
    columns = [np.ascontiguousarray(a).view(np.uint8).reshape(len(a), -1) for a in arrays]
    return np.hstack(columns).tobytes() if columns and len(columns[0]) else b""


def rings_bytes(rings):
    offsets = rings["offsets"]
    first = offsets[:-1].astype("<u4")
    count = np.diff(offsets).astype("<u4")
    records = le(rings["area"].astype("<f8"), first, count, rings["hole_of"].astype("<u4"))
    return records + rings["points"].astype("<f4").tobytes()


def test_the_scenes_are_read_from_the_rust_list():
    assert len(GOLDENS) >= 40
    assert "glass.plate160.mask" in GOLDENS


@pytest.fixture(scope="module")
def mud32():
    mud = hibi.Mud(columns=32, rows=32)
    mud.run()
    return mud


def test_mud_hex32_segments(mud32):
    assert fnv(mud32.segments().astype("<f4")) == GOLDENS["mud.hex32.f32.segments"]


def test_mud_hex32_network(mud32):
    n = mud32.network()
    h = fnv(le(n["vertices"].astype("<f4"), n["degree"].astype("<u4"), n["on_border"].astype("<u4")))
    offsets = n["offsets"]
    edges = le(
        n["from"].astype("<u4"),
        n["to"].astype("<u4"),
        offsets[:-1].astype("<u4"),
        np.diff(offsets).astype("<u4"),
    )
    h = fnv(edges, h)
    h = fnv(le(n["points"].astype("<f4"), n["width"].astype("<f4"), n["time"].astype("<f4")), h)
    assert h == GOLDENS["mud.hex32.f32.network"]


def test_mud_hex32_cells(mud32):
    cells = mud32.cells()
    h = fnv(rings_bytes(cells))
    h = fnv(np.array([cells["wrapping"]], "<u4"), h)
    assert h == GOLDENS["mud.hex32.f32.cells"]


@pytest.mark.parametrize("layer", ["mask", "time", "height"])
def test_mud_hex32_rasters(mud32, layer):
    image = mud32.render(layer, width=128, height=128)
    assert image.shape == (128, 128)
    assert fnv(image) == GOLDENS[f"mud.hex32.f32.{layer}"]


@pytest.mark.parametrize(
    "scene, params",
    [
        ("mud.hex64.f32.segments", dict(columns=64, rows=64)),
        ("mud.irregular32.f32.segments", dict(columns=32, rows=32, topology="irregular")),
        ("small.mud.hex16.f32.segments", dict(columns=16, rows=16)),
    ],
)
def test_mud_segments(scene, params):
    mud = hibi.Mud(**params)
    assert mud.run().finished
    assert fnv(mud.segments().astype("<f4")) == GOLDENS[scene]


def cracks_hash(glass):
    c = glass.cracks()
    h = FNV_OFFSET
    offsets = c["offsets"]
    points = c["points"].astype("<f4")
    time = c["time"].astype("<f4")
    for i, end in enumerate(c["end"]):
        h = fnv(np.array([end], "<u4"), h)
        a, b = offsets[i], offsets[i + 1]
        h = fnv(le(points[a:b], time[a:b]), h)
    return h


@pytest.fixture(scope="module")
def plate160():
    glass = hibi.Glass(width=160, height=160, seed=7)
    assert glass.params["impact"] == (80.0, 80.0)
    assert glass.run().finished
    return glass


def test_glass_plate160_cracks(plate160):
    assert cracks_hash(plate160) == GOLDENS["glass.plate160.cracks"]


def test_glass_plate160_fragments(plate160):
    assert fnv(rings_bytes(plate160.fragments())) == GOLDENS["glass.plate160.fragments"]


@pytest.mark.parametrize("layer", ["mask", "time"])
def test_glass_plate160_rasters(plate160, layer):
    image = plate160.render(layer)
    assert image.shape == (160, 160)
    assert fnv(image) == GOLDENS[f"glass.plate160.{layer}"]


def test_small_glass128():
    glass = hibi.Glass(width=128, height=128, seed=7, radial_mean=40, max_cracks=44, max_vertices=175)
    p = glass.run()
    assert p.finished and not p.capacity_reached
    assert cracks_hash(glass) == GOLDENS["small.glass128.cracks"]
    assert fnv(glass.render("mask")) == GOLDENS["small.glass128.mask"]


def outlines_hash(skin):
    cells = skin.cells()
    h = FNV_OFFSET
    offsets, fixed = cells["offsets"], cells["fixed"].astype("<i8")
    for i, site in enumerate(cells["site"]):
        h = fnv(np.array([site], "<u4"), h)
        h = fnv(fixed[offsets[i] : offsets[i + 1]], h)
    return h


@pytest.fixture(scope="module")
def fig19a():
    skin = hibi.Skin("fig19a", width=64, height=64)
    assert skin.run().finished
    return skin


def test_skin_fig19a_outlines(fig19a):
    assert outlines_hash(fig19a) == GOLDENS["skin.fig19a64.outlines"]


def test_skin_fig19a_maps(fig19a):
    maps = fig19a.render(["height", "normal"])
    assert maps["height"].shape == (64, 64) and maps["normal"].shape == (64, 64, 3)
    h = fnv(maps["height"].astype("<f4"))
    h = fnv(maps["normal"].astype("<f4"), h)
    assert h == GOLDENS["skin.fig19a64.f32.maps"]


def test_skin_fig19a_cell_maps(fig19a):
    h = FNV_OFFSET
    for level in range(fig19a.params["levels"]):
        h = fnv(fig19a.render("cell", cell_level=level).astype("<u4"), h)
    assert h == GOLDENS["skin.fig19a64.cell_maps"]


def test_small_skin64():
    skin = hibi.Skin("fig13a", width=64, height=64)
    assert skin.run().finished
    assert outlines_hash(skin) == GOLDENS["small.skin64.outlines"]
    assert fnv(skin.render("height").astype("<f4")) == GOLDENS["small.skin64.f32.height"]
