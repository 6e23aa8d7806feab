#!/usr/bin/python3
"""The Dask recipe of docs/scale-out.md on a LocalCluster of 2 workers: emo2muscle and faceanim run as
contiguous shards and their merged outputs equal the single-process outputs byte for byte.
Usage: dask_recipe_test.py SOURCE_DIR EMO2MUSCLE FACEANIM WORK_DIR"""
import filecmp
import os
import shutil
import subprocess
import sys


def main(source, emo2muscle, faceanim, work):
    sys.path.insert(0, os.path.join(source, "scripts"))
    import dask_shards
    from dask.distributed import Client, LocalCluster

    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    # 23 ESV rows (with a tie-break seed, so row r must keep stream r in every shard)
    esv = os.path.join(work, "esv.csv")
    with open(esv, "w") as f:
        f.write("id,sadness,happiness,anger,fear,disgust,surprise\n")
        for r in range(23):
            f.write(f"r{r},{(r % 5) / 5},{(r % 3) / 3},0.4,0.4,{(r % 7) / 7},0.1\n")
    # 6 parameter frames for faceanim (a smile that grows, a jaw that opens)
    params = os.path.join(work, "params.csv")
    with open(params, "w") as f:
        f.write("time,zygomatic_major_l,zygomatic_major_r,masseter\n")
        for k in range(6):
            f.write(f"{k / 10},{k / 6},{k / 6},{k / 12}\n")

    def run(argv):
        subprocess.run(argv, check=True, capture_output=True)

    n = 3
    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                           dashboard_address=None)
    client = Client(cluster)
    failures = []
    try:
        for to in ("csv", "ndjson"):
            whole = os.path.join(work, f"whole.{to}")
            common = ["--to", to, "--sides", "--tie-break", "random", "--seed", "9"]
            run([emo2muscle, esv, *common, "-o", whole])
            parts = [os.path.join(work, f"part{i}.{to}") for i in range(n)]
            dask_shards.run_on_dask(client, [emo2muscle, esv, *common, "--shard", "{i}/{n}", "-o",
                                             os.path.join(work, "part{i}." + to)], n)
            merged = os.path.join(work, f"merged.{to}")
            run([emo2muscle, "--merge", *parts, "-o", merged])
            if not filecmp.cmp(whole, merged, shallow=False):
                failures.append(f"emo2muscle --to {to}: merged shards differ from one run")
        single = os.path.join(work, "frames_single")
        sharded = os.path.join(work, "frames_sharded")
        run([faceanim, "--params", params, "--out", single])
        dask_shards.run_on_dask(client, [faceanim, "--params", params, "--out", sharded,
                                         "--shard", "{i}/{n}"], n)
        a, b = sorted(os.listdir(single)), sorted(os.listdir(sharded))
        if a != b or len(a) != 6:
            failures.append(f"faceanim: frame files differ: {a} vs {b}")
        else:
            match, mismatch, errors = filecmp.cmpfiles(single, sharded, a, shallow=False)
            if mismatch or errors:
                failures.append(f"faceanim: frames differ: {mismatch + errors}")
    finally:
        client.close()
        cluster.close()
    for f in failures:
        print("FAIL:", f)
    if not failures:
        print("dask recipe: emo2muscle (csv, ndjson) and faceanim shards merge to the single run")
    return 1 if failures else 0


if __name__ == "__main__":
    if len(sys.argv) != 5:
        print(__doc__)
        sys.exit(2)
    sys.exit(main(*sys.argv[1:]))
