"""Datasets: the same files on one process, a thread pool and a Dask cluster, whatever the
sharding; COCO polygons that lie on the cracks; nothing half-written."""

import hashlib
import json
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import hibi
from hibi import dataset

GLASS = dict(width=160.0, height=160.0)


def files(root):
    """Every file under `root` (path -> sha256), the dataset's description included."""
    out = {}
    for path in sorted(pathlib.Path(root).rglob("*")):
        if path.is_file():
            out[str(path.relative_to(root))] = hashlib.sha256(path.read_bytes()).hexdigest()
    return out


def merged(root):
    images, annotations = [], []
    for shard in dataset.shards(str(root)):
        coco = json.loads(pathlib.Path(shard, "annotations.json").read_text())
        images += coco["images"]
        annotations += coco["annotations"]
    return images, annotations


@pytest.fixture(scope="module")
def single(tmp_path_factory):
    out = tmp_path_factory.mktemp("single")
    spec = dataset.Spec("glass", 6, params=GLASS, first_seed=10, shard_size=2)
    seen = []
    dirs = dataset.write(str(out), spec, progress=seen.append)
    assert [os.path.basename(d) for d in dirs] == ["shard-00000", "shard-00001", "shard-00002"]
    assert sum(seen) == 6
    return out


def test_a_shard_holds_images_masks_and_coco_polygons(single):
    shard = pathlib.Path(single, "shard-00001")
    names = sorted(p.name for p in (shard / "images").iterdir())
    assert names == ["00000012.png", "00000013.png"]
    assert sorted(p.name for p in (shard / "masks").iterdir()) == names
    coco = json.loads((shard / "annotations.json").read_text())
    assert [i["id"] for i in coco["images"]] == [12, 13]
    assert coco["categories"] == [{"id": 1, "name": "fragment", "supercategory": "glass"}]
    ann = [a for a in coco["annotations"] if a["image_id"] == 12]
    assert len(ann) > 5
    # The fragments tile the plate.
    assert abs(sum(a["area"] for a in ann) - 160 * 160) < 2.0
    for a in ann:
        x, y, w, h = a["bbox"]
        ring = np.array(a["segmentation"][0]).reshape(-1, 2)
        assert np.allclose(ring.min(axis=0), [x, y], atol=0.011) and (w, h) >= (0, 0)
    text = (shard / "annotations.json").read_bytes()
    assert text == (json.dumps(coco, sort_keys=True, separators=(",", ":")) + "\n").encode()


def test_the_polygons_follow_the_mask(single):
    # Fragment outlines run along the cracks: the mask is set under their edges.
    import io
    import struct
    import zlib

    shard = pathlib.Path(single, "shard-00000")
    png = (shard / "masks" / "00000010.png").read_bytes()
    mask = hibi.Glass(seed=10, **GLASS)
    mask.run()
    mask = mask.render("mask")
    assert hibi.encode_png(mask) == png
    coco = json.loads((shard / "annotations.json").read_text())
    pts = np.concatenate([np.array(a["segmentation"][0]).reshape(-1, 2) for a in coco["annotations"]
                          if a["image_id"] == 10])
    inside = pts[(pts[:, 0] > 2) & (pts[:, 0] < 157) & (pts[:, 1] > 2) & (pts[:, 1] < 157)]
    on = mask[inside[:, 1].astype(int), inside[:, 0].astype(int)] > 0
    assert on.mean() > 0.95


def test_threads_and_other_shard_sizes_write_the_same_samples(single, tmp_path):
    spec = dataset.Spec("glass", 6, params=GLASS, first_seed=10, shard_size=2)
    dataset.write(str(tmp_path / "threads"), spec, workers=3)
    assert files(tmp_path / "threads") == files(single)
    other = dataset.Spec("glass", 6, params=GLASS, first_seed=10, shard_size=4)
    dataset.write(str(tmp_path / "fours"), other)
    strip = lambda fs: {k.split("/", 1)[1]: v for k, v in fs.items() if "/" in k and "annotations" not in k}
    assert strip(files(tmp_path / "fours")) == strip(files(single))
    assert merged(tmp_path / "fours") == merged(single)


def test_dask_local_cluster_writes_the_same_bytes(single, tmp_path):
    distributed = pytest.importorskip("distributed")
    spec = dataset.Spec("glass", 6, params=GLASS, first_seed=10, shard_size=2)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        dataset.write(str(tmp_path / "dask"), spec, client=client)
        workers = client.run(os.getpid)
    assert len(set(workers.values())) == 2
    assert files(tmp_path / "dask") == files(single)


def test_an_interrupted_run_leaves_no_half_shard_and_resumes(tmp_path, monkeypatch):
    spec = dataset.Spec("mud", 3, params=dict(columns=16, rows=16), shard_size=1, size=(64, 64))
    real = dataset.sample

    def failing(spec_, seed):
        if seed == 1:
            raise KeyboardInterrupt
        return real(spec_, seed)

    monkeypatch.setattr(dataset, "sample", failing)
    with pytest.raises(KeyboardInterrupt):
        dataset.write(str(tmp_path), spec)
    assert sorted(os.listdir(tmp_path)) == ["dataset.json", "shard-00000"]
    monkeypatch.setattr(dataset, "sample", real)
    dataset.write(str(tmp_path), spec)
    assert sorted(os.listdir(tmp_path)) == ["dataset.json", "shard-00000", "shard-00001", "shard-00002"]
    with pytest.raises(ValueError, match="another dataset"):
        dataset.write(str(tmp_path), dataset.Spec("mud", 4, params=dict(columns=16, rows=16), shard_size=1))


def test_bad_dataset_input_names_the_field():
    with pytest.raises(ValueError, match="count"):
        dataset.Spec("glass", 0)
    with pytest.raises(ValueError, match="model"):
        dataset.Spec("stone", 3)
    with pytest.raises(ValueError, match="radial_mean"):
        dataset.Spec("glass", 3, params=dict(radial_mean=-4.0))
    with pytest.raises(ValueError, match="seed"):
        dataset.Spec("glass", 3, params=dict(seed=4))


def test_the_command_line_writes_a_dataset(tmp_path):
    out = tmp_path / "cli"
    run = subprocess.run(
        [sys.executable, "-m", "hibi.dataset", "skin", str(out), "--count", "2", "--shard-size", "1",
         "--preset", "fig13a", "--size", "96x80", "--quiet"],
        capture_output=True, text=True,
    )
    assert run.returncode == 0, run.stderr
    coco = json.loads((out / "shard-00001" / "annotations.json").read_text())
    assert coco["images"][0]["width"] == 96 and coco["images"][0]["height"] == 80
    assert len(coco["annotations"]) > 3
    bad = subprocess.run([sys.executable, "-m", "hibi.dataset", "glass", str(tmp_path / "bad"), "--count", "1",
                          "--param", "turn_limit=9"], capture_output=True, text=True)
    assert bad.returncode == 2 and "turn_limit" in bad.stderr
    assert not (tmp_path / "bad").exists()
