"""Speed of the Python package: dataset samples per second at 1 and 2 workers, and the time
one Python call takes over the same work done in Rust.

    python python/bench.py [--samples N] [--repeats R] [--dask]

Run it with the interpreter hibi is installed in (python/test's venv: target/python-venv).
Scenes: "mud256", the default mud lattice with 148 rows (a square domain) drawn 256 x 256,
and "glass640", the paper's default 640 x 640 plate drawn one pixel per px.

- Overhead: the Python calls (build the model, run it, render its mask) against the same work
  done straight through hibi-core in Rust (python/src/reference.rs, in the extension, so in
  the same build and process); CPU time of each (time.process_time), the two alternated R
  times, medians.
- Throughput: hibi.dataset writing N samples (preview PNG, mask PNG, COCO polygons) with 1
  and 2 worker threads (and with --dask, a LocalCluster of 2 worker processes).
"""

import argparse
import resource
import statistics
import tempfile
import time

import hibi
from hibi import dataset

def python_scene(name):
    if name == "mud256":
        m = hibi.Mud(rows=148)
        m.run()
        return m.render("mask", width=256, height=256)
    g = hibi.Glass()
    g.run()
    return g.render("mask")


def overhead(name, repeats):
    """Median CPU seconds of the Rust reference and of the Python calls, alternated."""
    from hibi._hibi import _reference

    rust, python = [], []
    for _ in range(repeats):
        start = time.process_time()
        _reference(name)
        rust.append(time.process_time() - start)
        start = time.process_time()
        python_scene(name)
        python.append(time.process_time() - start)
    return statistics.median(rust), statistics.median(python)


SPECS = {
    "mud256": lambda n: dataset.Spec("mud", n, params=dict(rows=148), size=(256, 256), shard_size=1),
    "glass640": lambda n: dataset.Spec("glass", n, shard_size=1),
}


def cpu():
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def throughput(name, samples, workers=1, client=None):
    """Samples per second, and the cores this process used on average (CPU time / wall)."""
    spec = SPECS[name](samples)
    with tempfile.TemporaryDirectory() as out:
        start, used = time.perf_counter(), cpu()
        dataset.write(out, spec, workers=workers, client=client)
        wall = time.perf_counter() - start
        return samples / wall, (cpu() - used) / wall


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--samples", type=int, default=16, help="samples per dataset (default 16)")
    parser.add_argument("--repeats", type=int, default=41, help="repeats of the overhead's pair (default 41)")
    parser.add_argument("--dask", action="store_true", help="also a Dask LocalCluster of 2 worker processes")
    args = parser.parse_args()
    print("CPU time of one call: Rust reference, Python")
    print("scene     rust median   python median   python/rust")
    for name in ("mud256", "glass640"):
        r, p = overhead(name, args.repeats)
        print(f"{name:9} {r * 1e3:9.2f} ms {p * 1e3:12.2f} ms   {p / r:8.3f}x  ({(p / r - 1) * 100:+.1f} %)")
    client = cluster = None
    if args.dask:
        import distributed

        cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
        client = distributed.Client(cluster)
        client.run(lambda: __import__("hibi"))
    print("samples per second (cores used: this process's CPU time / wall time)")
    print("scene     1 worker (cores)   2 workers (cores)   2/1" + ("   dask 2 workers   dask/1" if args.dask else ""))
    for name in ("mud256", "glass640"):
        throughput(name, 2)  # warm up: page in the library, the files' directories
        one, c1 = throughput(name, args.samples, workers=1)
        two, c2 = throughput(name, args.samples, workers=2)
        line = f"{name:9} {one:8.2f} ({c1:4.2f}) {two:11.2f} ({c2:4.2f})   {two / one:5.2f}x"
        if client is not None:
            d, _ = throughput(name, args.samples, client=client)
            line += f" {d:16.2f} {d / one:8.2f}x"
        print(line)
    if client is not None:
        client.close()
        cluster.close()


if __name__ == "__main__":
    main()
