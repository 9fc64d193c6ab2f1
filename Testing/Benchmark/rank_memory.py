"""Peak memory of every rank, meshing over MPI ranks: `mpiexec -n N pvbatch` with the one-shot
filter (Testing/Python/mpi_mesh.py, without deformation, or with it after --deformed), each
rank's pvbatch under `/usr/bin/time`, against the same run on one process.

    python3 Testing/Benchmark/rank_memory.py [--deformed] PLUGIN IMAGE [RANKS[:HALO[:tissue]] ...]

RANKS:HALO gives the halo in lattice cubes (Rank Halo; 4 when left out), e.g. `2 3 3:2`; a third
field `tissue` cuts slabs of even tissue boundary (Balance Tissue), e.g. `3:4:tissue`. Prints
one line a run: ranks, halo, slabs, seconds, tets, each rank's peak (GB), and the largest as a
share of the one-process run's. Nothing is asserted: the issue's target is a share of 45% on 3 ranks.
"""
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
DRIVER = os.path.join(HERE, "..", "Python", "mpi_mesh.py")


def environment():
    """This process's environment for mpiexec, without another MPI job's variables."""
    return {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_", "ORTE_"))}


def run(plugin, image, ranks, halo, balanced, work, deformed):
    """Seconds, tets and each rank's peak resident GB of one run."""
    timing = os.path.join(work, "rank-%q.txt")
    for name in os.listdir(work):
        os.remove(os.path.join(work, name))
    command = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-n", str(ranks), "bash", "-c",
               '/usr/bin/time -o "%s" -f "%%e %%M" "$@"' % timing.replace("%q", "$OMPI_COMM_WORLD_RANK"),
               "time", "pvbatch", DRIVER, plugin, image, "RankHalo=%s" % float(halo),
               "BalanceTissue=%d" % balanced]
    if not deformed:
        command.append("DeformationIterations=0")
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=environment())
    tets = re.search(r"mpi_mesh: \d+ ranks, (\d+) tets", result.stdout)
    if result.returncode != 0 or not tets:
        raise RuntimeError("%d ranks, halo %s failed: %s" % (ranks, halo, result.stdout[-500:]))
    peaks, seconds = [], 0.0
    for rank in range(ranks):
        with open(timing.replace("%q", str(rank))) as f:
            wall, kilobytes = f.read().split()[-2:]
        peaks.append(int(kilobytes) / 1e6)
        seconds = max(seconds, float(wall))
    return seconds, int(tets.group(1)), peaks


def main(argv):
    deformed = "--deformed" in argv
    argv = [a for a in argv if a != "--deformed"]
    if len(argv) < 3:
        print(__doc__)
        return 2
    plugin, image = argv[1:3]
    runs = [(1, 4, False)]
    for spec in argv[3:] or ["2", "3"]:
        fields = spec.split(":")
        runs.append((int(fields[0]), fields[1] if len(fields) > 1 else 4, fields[2:] == ["tissue"]))
    print("%-6s %-5s %-7s %9s %10s  %-24s %s" % ("ranks", "halo", "slabs", "seconds", "tets", "peak per rank (GB)",
                                               "largest / 1 rank"))
    serial = None
    with tempfile.TemporaryDirectory() as work:
        for ranks, halo, balanced in runs:
            seconds, tets, peaks = run(plugin, image, ranks, halo, balanced, work, deformed)
            serial = serial or max(peaks)
            print("%-6d %-5s %-7s %9.1f %10d  %-24s %3.0f%%" % (
                ranks, "-" if ranks == 1 else halo, "-" if ranks == 1 else "tissue" if balanced else "slices",
                seconds, tets, ", ".join("%.2f" % p for p in peaks),
                100.0 * max(peaks) / serial))
            sys.stdout.flush()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
