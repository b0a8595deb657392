"""Reading an HDF5 time series (`drumlab run --h5`) and plotting the granule size distribution
of its first and last frame (agglomerates by the series' agglomerate_id).

    ./drumlab run scenes/granulation_small.toml --h5 out/g.h5 --every 500
    ./drumlab python app/python/examples/series_psd.py out/g.h5 [--out psd.png]
"""
import argparse
import collections

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import drumlab

parser = argparse.ArgumentParser()
parser.add_argument("series")
parser.add_argument("--out", default="psd.png")
args = parser.parse_args()

frames = drumlab.read_series(args.series)
print(f"{len(frames)} frames, t = {frames[0]['time']:.3f} .. {frames[-1]['time']:.3f} s")
for frame in (frames[0], frames[-1]):
    if "agglomerate_id" not in frame:
        raise SystemExit(f"{args.series}: the frames carry no agglomerates (a dry scene)")
    volume = collections.defaultdict(float)
    for aid, r in zip(frame["agglomerate_id"], frame["radius"]):
        volume[int(aid)] += 4.0 / 3.0 * np.pi * r**3
    d = np.sort((6.0 / np.pi * np.array(list(volume.values())))**(1.0 / 3.0))
    v = np.sort(np.array(list(volume.values())))
    cumulative = np.cumsum(v) / np.sum(v)
    plt.step(d * 1e3, cumulative, where="post", label=f"t = {frame['time']:.2f} s")
    print(f"t = {frame['time']:.3f} s: {len(d)} granules, largest {d[-1] * 1e3:.2f} mm")
plt.xlabel("granule diameter (volume-equivalent), mm")
plt.ylabel("cumulative volume share")
plt.legend()
plt.savefig(args.out, dpi=100)
print(f"chart {args.out}")
