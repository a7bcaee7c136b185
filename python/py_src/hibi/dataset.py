"""Crack datasets: N samples of a model, each an image, a crack mask and its polygons.

A dataset is a directory::

    OUT/dataset.json                    what was asked: model, params, size, seeds, shards
    OUT/shard-00000/images/00000000.png the model's shaded preview (RGBA, 8 bits)
    OUT/shard-00000/masks/00000000.png  the crack mask (grey, 8 bits: 0 none to 255 full)
    OUT/shard-00000/annotations.json    COCO: images, annotations (polygons), categories

Sample ``k`` is the model run with ``seed = first_seed + k``; its file names are its seed.
Shard ``s`` holds samples ``s * shard_size`` up to the next shard's. Every file is a function
of the model, its parameters, the size and the seeds only: one process, a thread pool and a
Dask cluster write the same bytes. Image and annotation ids are the seed (annotations
``seed * 100000 + k``), so the shards' annotations concatenate into the same list whatever
``shard_size`` is. PNGs come from :func:`hibi.encode_png` (the Rust ``png`` crate at a pinned
version); JSON is written with sorted keys, no spaces and coordinates rounded to 1/100 px.

The polygons are the model's regions in image pixels: glass fragments, mud cells (the cells
that wrap around a periodic lattice have no outline in the plane and are left out), skin
cells of the coarsest level. An outer ring is ``segmentation``; its holes, if any, are
``holes`` (COCO readers ignore the key) and their area is taken off ``area``.

Each shard is written into a temporary directory and renamed into place when complete, so an
interrupted run leaves no half-written shard; running again writes only the missing shards.

Command line: ``python -m hibi.dataset MODEL OUT --count N [--shard-size S] [--workers W]
[--threads | --scheduler ADDRESS] [--param NAME=VALUE ...]``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import shutil
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor, as_completed
from typing import Any, Callable, Dict, Iterable, List, Optional, Sequence, Tuple

import numpy as np

from . import Glass, Mud, Skin, encode_png

__all__ = ["Spec", "sample", "write", "write_shard", "shards", "main"]

MODELS = {"mud": Mud, "glass": Glass, "skin": Skin}
CATEGORY = {"mud": "cell", "glass": "fragment", "skin": "cell"}
ANNOTATIONS_PER_IMAGE = 100_000
FORMAT = 1


class Spec:
    """What a dataset holds: ``model`` ("mud", "glass" or "skin"), its ``params`` (keyword
    arguments of the model, with ``preset``), the image ``size`` (width, height; default the
    model's own: the glass plate's, 512 wide for mud, the skin's), ``count`` samples from
    ``first_seed`` on, ``shard_size`` samples a shard."""

    def __init__(
        self,
        model: str,
        count: int,
        *,
        params: Optional[Dict[str, Any]] = None,
        size: Optional[Tuple[int, int]] = None,
        first_seed: int = 0,
        shard_size: int = 100,
    ) -> None:
        if model not in MODELS:
            raise ValueError(f"dataset: model must be one of {', '.join(MODELS)}, not {model!r}")
        if not (isinstance(count, int) and count >= 1):
            raise ValueError("dataset: count must be an integer >= 1")
        if not (isinstance(shard_size, int) and shard_size >= 1):
            raise ValueError("dataset: shard_size must be an integer >= 1")
        if not (isinstance(first_seed, int) and 0 <= first_seed and first_seed + count <= 2**64):
            raise ValueError("dataset: first_seed must be an integer >= 0, first_seed + count <= 2^64")
        params = dict(params or {})
        if "seed" in params:
            raise ValueError("dataset: params must not hold seed (the samples' seeds are first_seed + k)")
        if size is not None:
            size = (int(size[0]), int(size[1]))
            if min(size) < 1:
                raise ValueError("dataset: size must be two integers >= 1")
        self.model, self.count, self.params = model, count, params
        self.size, self.first_seed, self.shard_size = size, first_seed, shard_size
        # Bad parameters are refused here, naming the field, before any work.
        self.build(first_seed)

    def to_json(self) -> Dict[str, Any]:
        return {
            "format": FORMAT,
            "model": self.model,
            "params": self.params,
            "size": list(self.size) if self.size else None,
            "count": self.count,
            "first_seed": self.first_seed,
            "shard_size": self.shard_size,
        }

    @classmethod
    def from_json(cls, d: Dict[str, Any]) -> "Spec":
        size = tuple(d["size"]) if d.get("size") else None
        return cls(
            d["model"],
            d["count"],
            params=d["params"],
            size=size,  # type: ignore[arg-type]
            first_seed=d["first_seed"],
            shard_size=d["shard_size"],
        )

    def build(self, seed: int) -> Any:
        params = dict(self.params)
        preset = params.pop("preset", None)
        if self.model == "skin" and self.size is not None:
            params.setdefault("width", self.size[0])
            params.setdefault("height", self.size[1])
        return MODELS[self.model](preset, seed=seed, **params)

    @property
    def shard_count(self) -> int:
        return math.ceil(self.count / self.shard_size)

    def seeds(self, shard: int) -> range:
        start = self.first_seed + shard * self.shard_size
        return range(start, min(start + self.shard_size, self.first_seed + self.count))


def _round(v: float) -> float:
    r = round(float(v), 2)
    return 0.0 if r == 0 else r


def _polygons(spec: Spec, model: Any, width: int, height: int) -> Tuple[Dict[str, Any], float, float]:
    """The model's regions and the scale from their units to image pixels."""
    if spec.model == "glass":
        rings = model.fragments()
        p = model.params
        return rings, width / p["width"], height / p["height"]
    if spec.model == "mud":
        rings = model.cells()
        ew, eh = model.extent
        return rings, width / ew, height / eh
    cells = model.cells()
    keep = np.flatnonzero(cells["level"] == 0)
    offsets = cells["offsets"]
    points = [cells["points"][offsets[k] : offsets[k + 1]] for k in keep]
    counts = [len(p) for p in points]
    pts = np.concatenate(points) if points else np.zeros((0, 2))
    # Outline areas by the shoelace formula (counter-clockwise with y up: positive).
    areas = [0.5 * float(np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])) for p in points]
    rings = {
        "points": pts,
        "offsets": np.concatenate([[0], np.cumsum(counts)]).astype(np.int64),
        "area": np.abs(np.array(areas, dtype=np.float64)),
        "hole_of": np.full(len(points), 0xFFFFFFFF, dtype=np.uint32),
    }
    return rings, 1.0, 1.0


def _annotations(spec: Spec, model: Any, seed: int, width: int, height: int) -> List[Dict[str, Any]]:
    rings, sx, sy = _polygons(spec, model, width, height)
    offsets = np.asarray(rings["offsets"], dtype=np.int64)
    hole_of, area = rings["hole_of"], rings["area"]
    # Image pixels rounded to 1/100 (+ 0.0 turns -0.0 into 0.0).
    scaled = np.round(np.asarray(rings["points"], dtype=np.float64).reshape(-1, 2) * np.array([sx, sy]), 2) + 0.0
    counts = np.diff(offsets)
    rings_total = len(counts)
    holes: Dict[int, List[int]] = {}
    for k in np.flatnonzero(hole_of != 0xFFFFFFFF):
        if hole_of[k] < rings_total:
            holes.setdefault(int(hole_of[k]), []).append(int(k))
    out = []
    for k in np.flatnonzero((hole_of == 0xFFFFFFFF) & (counts >= 3)):
        ring = scaled[offsets[k] : offsets[k + 1]]
        (x0, y0), (x1, y1) = ring.min(axis=0).tolist(), ring.max(axis=0).tolist()
        a = (float(area[k]) + sum(float(area[j]) for j in holes.get(int(k), []))) * sx * sy
        entry = {
            "id": seed * ANNOTATIONS_PER_IMAGE + len(out),
            "image_id": seed,
            "category_id": 1,
            "segmentation": [ring.reshape(-1).tolist()],
            "area": _round(abs(a)),
            "bbox": [x0, y0, _round(x1 - x0), _round(y1 - y0)],
            "iscrowd": 0,
        }
        if int(k) in holes:
            entry["holes"] = [scaled[offsets[j] : offsets[j + 1]].reshape(-1).tolist() for j in holes[int(k)]]
        out.append(entry)
        if len(out) == ANNOTATIONS_PER_IMAGE:
            break
    return out


def sample(spec: Spec, seed: int) -> Dict[str, Any]:
    """One sample: the model run with ``seed`` to its end, its ``image`` (RGBA preview) and
    ``mask`` as arrays, and its COCO ``annotations``."""
    model = spec.build(seed)
    progress = model.run()
    if getattr(progress, "capacity_reached", False):
        raise RuntimeError(f"dataset: seed {seed}: the model ran out of capacity (raise max_cracks/max_vertices)")
    if spec.model == "skin":
        layers = model.render(["preview", "mask"])
    elif spec.model == "glass":
        w, h = spec.size or (None, None)
        layers = model.render(["preview", "mask"], width=w, height=h)
    else:
        w, h = spec.size or (512, None)
        layers = model.render(["preview", "mask"], width=w, height=h)
    height, width = layers["mask"].shape
    return {
        "seed": seed,
        "width": width,
        "height": height,
        "image": layers["preview"],
        "mask": layers["mask"],
        "annotations": _annotations(spec, model, seed, width, height),
    }


def _dumps(value: Any) -> bytes:
    return (json.dumps(value, sort_keys=True, separators=(",", ":"), allow_nan=False) + "\n").encode()


def shard_name(shard: int) -> str:
    return f"shard-{shard:05d}"


def write_shard(out: str, spec_json: Dict[str, Any], shard: int) -> Tuple[int, int]:
    """Writes shard ``shard`` of the dataset ``spec_json`` (:meth:`Spec.to_json`) under
    ``out`` unless it is there already; returns (shard, samples). Safe to run anywhere that
    sees ``out`` (a Dask worker on a shared file system)."""
    spec = Spec.from_json(spec_json)
    final = os.path.join(out, shard_name(shard))
    seeds = spec.seeds(shard)
    if os.path.isdir(final):
        return shard, len(seeds)
    temp = tempfile.mkdtemp(prefix=f".{shard_name(shard)}.", dir=out)
    try:
        os.mkdir(os.path.join(temp, "images"))
        os.mkdir(os.path.join(temp, "masks"))
        images, annotations = [], []
        for seed in seeds:
            s = sample(spec, seed)
            name = f"{seed:08d}.png"
            for folder, key in (("images", "image"), ("masks", "mask")):
                with open(os.path.join(temp, folder, name), "wb") as f:
                    f.write(encode_png(s[key]))
            images.append({"id": seed, "file_name": f"images/{name}", "mask_file_name": f"masks/{name}",
                           "width": s["width"], "height": s["height"], "seed": seed})
            annotations.extend(s["annotations"])
        coco = {
            "images": images,
            "annotations": annotations,
            "categories": [{"id": 1, "name": CATEGORY[spec.model], "supercategory": spec.model}],
        }
        with open(os.path.join(temp, "annotations.json"), "wb") as f:
            f.write(_dumps(coco))
        os.rename(temp, final)
    except BaseException:
        shutil.rmtree(temp, ignore_errors=True)
        raise
    return shard, len(seeds)


def _prepare(out: str, spec: Spec) -> None:
    os.makedirs(out, exist_ok=True)
    path = os.path.join(out, "dataset.json")
    want = spec.to_json()
    if os.path.exists(path):
        with open(path, "rb") as f:
            have = json.loads(f.read())
        if have != json.loads(_dumps(want)):
            raise ValueError(f"dataset: {out} holds another dataset (its dataset.json differs): use another directory")
        return
    with tempfile.NamedTemporaryFile("wb", dir=out, prefix=".dataset.json.", delete=False) as f:
        f.write(_dumps(want))
    os.replace(f.name, path)


def write(
    out: str,
    spec: Spec,
    *,
    workers: int = 1,
    client: Any = None,
    progress: Optional[Callable[[int], Any]] = None,
) -> List[str]:
    """Writes every shard of ``spec`` under ``out`` (created if needed) and returns the
    shard directories. ``workers`` > 1 writes shards on a thread pool (the models release
    the GIL); a ``dask.distributed.Client`` writes them on its cluster's workers, which must
    see ``out``. ``progress(n)`` is called with the samples of each shard as it completes."""
    _prepare(out, spec)
    spec_json = spec.to_json()
    todo = list(range(spec.shard_count))
    done = lambda n: progress(n) if progress else None  # noqa: E731
    if client is not None:
        from distributed import as_completed as dask_completed

        futures = client.map(write_shard, [out] * len(todo), [spec_json] * len(todo), todo, pure=False)
        for future in dask_completed(futures):
            done(future.result()[1])
    elif workers > 1:
        with ThreadPoolExecutor(workers) as pool:
            for future in as_completed([pool.submit(write_shard, out, spec_json, s) for s in todo]):
                done(future.result()[1])
    else:
        for s in todo:
            done(write_shard(out, spec_json, s)[1])
    return [os.path.join(out, shard_name(s)) for s in todo]


def shards(out: str) -> List[str]:
    """The shard directories of the dataset in ``out``, in order."""
    return sorted(os.path.join(out, d) for d in os.listdir(out) if d.startswith("shard-"))


def _value(text: str) -> Any:
    try:
        return json.loads(text)
    except ValueError:
        return text


class _Count:
    """A progress count on stderr, for when tqdm is not installed."""

    def __init__(self, total: int) -> None:
        self.total, self.done = total, 0

    def update(self, n: int) -> None:
        self.done += n
        print(f"\r{self.done}/{self.total} samples", end="", file=sys.stderr, flush=True)

    def close(self) -> None:
        print(file=sys.stderr)


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m hibi.dataset",
        description="Writes a crack dataset: images, masks and COCO polygons, in shards.",
    )
    parser.add_argument("model", choices=sorted(MODELS))
    parser.add_argument("out", help="the dataset's directory (created if needed)")
    parser.add_argument("--count", type=int, required=True, help="samples")
    parser.add_argument("--first-seed", type=int, default=0, help="seed of the first sample (default 0)")
    parser.add_argument("--shard-size", type=int, default=100, help="samples per shard (default 100)")
    parser.add_argument("--size", help="image size WxH (default the model's own)")
    parser.add_argument("--preset", help="the model's preset (a figure of its paper)")
    parser.add_argument("--param", action="append", default=[], metavar="NAME=VALUE",
                        help="a model parameter (VALUE as JSON, e.g. columns=64 or impact=[100,80])")
    parser.add_argument("--workers", type=int, default=1, help="threads writing shards (default 1)")
    parser.add_argument("--scheduler", help="address of a Dask scheduler to write the shards on")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")
    args = parser.parse_args(argv)
    params: Dict[str, Any] = {}
    if args.preset:
        params["preset"] = args.preset
    for item in args.param:
        name, sep, value = item.partition("=")
        if not sep:
            parser.error(f"--param {item}: expected NAME=VALUE")
        params[name] = _value(value)
    size = None
    if args.size:
        try:
            w, h = args.size.lower().split("x")
            size = (int(w), int(h))
        except ValueError:
            parser.error(f"--size {args.size}: expected WxH, e.g. 640x640")
    try:
        spec = Spec(args.model, args.count, params=params, size=size, first_seed=args.first_seed,
                    shard_size=args.shard_size)
    except (ValueError, TypeError) as e:
        print(f"python -m hibi.dataset: {e}", file=sys.stderr)
        return 2
    client = None
    if args.scheduler:
        from distributed import Client

        client = Client(args.scheduler)
    bar = None
    if not args.quiet:
        try:
            from tqdm import tqdm

            bar = tqdm(total=spec.count, unit="sample", desc=args.model)
        except ImportError:  # tqdm is optional: a plain count on stderr
            bar = _Count(spec.count)
    try:
        write(args.out, spec, workers=args.workers, client=client, progress=bar.update if bar else None)
    finally:
        if bar:
            bar.close()
        if client is not None:
            client.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
