"""A design study too large for one machine's patience, on Dask.

Splits a study of many four-bar designs (coupler b and rocker c drawn at random) into
chunks, each run by a Dask worker as kinema's Model.study on its chunk, and concatenates
the rows. Each worker loads the model from the file's text (kinema.loads): a model is not
sent over the network, only the text, the designs and the figures.

  PYTHONPATH=build/python python3 examples/dask_study.py --designs 100000
  PYTHONPATH=build/python python3 examples/dask_study.py --scheduler tcp://scheduler:8786

Without --scheduler a LocalCluster of --workers processes runs here; with it, the same code
runs on that cluster (each of its workers needs the kinema module importable).
"""
import argparse
import pathlib
import time

import numpy as np

import kinema

SAMPLE = pathlib.Path(__file__).resolve().parent.parent / "samples" / "four_bar.toml"


def study_chunk(text, name, designs, sweep, threads):
    """One worker's share: the model read from its text, its designs solved."""
    return kinema.loads(text, name).study(designs, sweep=sweep, threads=threads)


def random_designs(count, seed=0):
    """Coupler and rocker lengths (m) around the sample's 120 mm and 80 mm."""
    rng = np.random.default_rng(seed)
    return {"b": rng.uniform(0.100, 0.140, count), "c": rng.uniform(0.060, 0.100, count)}


def distributed_study(client, text, name, designs, sweep, chunks, threads=1):
    """The study of `designs` in `chunks` pieces on the client's cluster, rows in order."""
    count = len(next(iter(designs.values())))
    bounds = np.linspace(0, count, chunks + 1).astype(int)
    futures = [
        client.submit(study_chunk, text, name, {k: v[a:b] for k, v in designs.items()}, sweep, threads, pure=False)
        for a, b in zip(bounds[:-1], bounds[1:])
        if b > a
    ]
    return np.concatenate(client.gather(futures))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--designs", type=int, default=1_000_000, help="designs in the study (default 10^6)")
    parser.add_argument("--file", default=str(SAMPLE), help="the mechanism file (default: samples/four_bar.toml)")
    parser.add_argument("--scheduler", help="a running cluster's scheduler, e.g. tcp://scheduler:8786")
    parser.add_argument("--workers", type=int, default=2, help="workers of the local cluster (default 2)")
    parser.add_argument("--chunks", type=int, default=0, help="pieces of the study (default: 4 a worker)")
    parser.add_argument("-o", "--output", help="write the rows as .npy")
    args = parser.parse_args()

    from dask.distributed import Client, LocalCluster

    text = pathlib.Path(args.file).read_text()
    designs = random_designs(args.designs)
    sweep = ("0 deg", "360 deg", "1 deg")
    cluster = None if args.scheduler else LocalCluster(n_workers=args.workers, threads_per_worker=1)
    with Client(args.scheduler or cluster) as client:
        workers = len(client.scheduler_info()["workers"])
        start = time.perf_counter()
        rows = distributed_study(client, text, args.file, designs, sweep, args.chunks or 4 * workers)
        seconds = time.perf_counter() - start
    if cluster is not None:
        cluster.close()
    print(f"{len(rows)} designs x 361 values on {workers} workers: {seconds:.2f} s "
          f"({len(rows) * 361 / seconds / 1e6:.1f} million values a second)")
    print("crank-rockers:", int(np.sum(rows["grashof"] == kinema.GRASHOF_CLASSES.index("crank-rocker"))),
          "least transmission angle above 40 deg:", int(np.sum(rows["min_transmission_angle"] > np.radians(40))))
    if args.output:
        np.save(args.output, rows)


if __name__ == "__main__":
    main()
