#!/usr/bin/python3
"""Run an emoface CLI as N contiguous shards on a Dask cluster (docs/scale-out.md, issue 18).

  scripts/dask_shards.py --local-workers 2 --shards 4 -- \\
      build/apps/emo2muscle/emo2muscle in.csv --shard {i}/{n} -o out/part{i}.csv
  build/apps/emo2muscle/emo2muscle --merge out/part0.csv out/part1.csv ... -o out/all.csv

The command after "--" is run once per shard with {i} (shard index) and {n} (shard count) replaced;
every shard runs as a separate process on a Dask worker (subprocess), so emoface needs no Python
bindings and the workers only need the built CLI on a shared file system. --scheduler ADDRESS uses a
running cluster (dask-scheduler / dask-worker, dask-jobqueue on Slurm, Kubernetes, ...);
--local-workers K starts a LocalCluster of K worker processes on this machine.
A shard that fails (non-zero exit) fails the run with its stderr; outputs are the CLI's own (atomic).
"""
import argparse
import subprocess
import sys


def run_shard(argv):
    """Runs one shard's command on a worker; returns its stderr, raises on a non-zero exit."""
    result = subprocess.run(argv, capture_output=True, text=True, check=False)
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(argv)}: exit {result.returncode}: {result.stderr.strip()}")
    return result.stderr


def shard_commands(template, count):
    """The command of each shard: {i} and {n} replaced in every argument."""
    return [[arg.replace("{i}", str(i)).replace("{n}", str(count)) for arg in template]
            for i in range(count)]


def run_on_dask(client, template, count):
    """Runs the `count` shards of `template` on the cluster of `client`; returns their stderr texts
    in shard order (raises the first failure)."""
    futures = client.map(run_shard, shard_commands(template, count), pure=False)
    return client.gather(futures)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    where = parser.add_mutually_exclusive_group(required=True)
    where.add_argument("--scheduler", help="address of a running Dask scheduler (tcp://host:8786)")
    where.add_argument("--local-workers", type=int, help="start a LocalCluster of this many workers")
    parser.add_argument("--shards", type=int, required=True, help="number of shards N (>= 1)")
    parser.add_argument("command", nargs=argparse.REMAINDER,
                        help="-- then the CLI command with {i} and {n}")
    args = parser.parse_args(argv)
    command = args.command[1:] if args.command[:1] == ["--"] else args.command
    if not command or args.shards < 1:
        parser.error("give --shards N >= 1 and a command after --")
    if not any("{i}" in a for a in command):
        parser.error("the command must contain {i} (e.g. --shard {i}/{n} -o part{i}.csv)")
    from dask.distributed import Client, LocalCluster  # Debian: python3-distributed
    if args.scheduler:
        client = Client(args.scheduler)
        cluster = None
    else:
        cluster = LocalCluster(n_workers=args.local_workers, threads_per_worker=1,
                               processes=True, dashboard_address=None)
        client = Client(cluster)
    try:
        for i, err in enumerate(run_on_dask(client, command, args.shards)):
            if err.strip():
                print(f"shard {i}: {err.strip()}", file=sys.stderr)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
