#!/usr/bin/env python3
"""raylab-bench's Targets table agrees with itself, round by round.

  check_bench_targets.py [--skip-if-untimed] BENCH ARGS...

Runs BENCH with ARGS (which must include --repeats N) and reads the Targets table at the
end of its output: | what | measured | target | met | rounds met | per round |. For every
row timed in rounds (rounds met is not "-"):
- rounds met is "k of N", 0 <= k <= N, N the run's --repeats;
- per round is "median (lo - hi)", the unit after the median as measured has it,
  lo <= median <= hi, no NaN;
- with N = 1, the one round is the median: lo = median = hi = measured, and met is "yes"
  exactly when k is 1 (a per-round figure taken the wrong way round, Embree's speed over
  raylab's, or another work's time, breaks one of these).
At least one row must be timed in rounds: the Cornell box's frame at 640x480 on two
threads is (ARGS --sections render --size 640x480 --threads 2); section 2's ratios to
Embree are only where raylab-bench was built with the Embree peer, so with
--skip-if-untimed a run without such a row is skipped (exit 77) instead of failed.

Exits 0 when every row agrees, 1 with one line per problem.
"""
import re
import subprocess
import sys

NUMBER = r"(-?[0-9.]+(?:e[-+]?[0-9]+)?|nan|-?inf)"


def cells(line):
    return [c.strip() for c in line.strip().strip("|").split("|")]


def main():
    argv = sys.argv[1:]
    skip_if_untimed = argv[0] == "--skip-if-untimed"
    bench, args = argv[int(skip_if_untimed)], argv[int(skip_if_untimed) + 1 :]
    repeats = int(args[args.index("--repeats") + 1])
    out = subprocess.run([bench, *args], capture_output=True, text=True, check=True).stdout
    sys.stdout.write(out)
    lines = out.splitlines()
    if "## Targets" not in lines:
        if skip_if_untimed:
            print("no Targets table (raylab-bench without the Embree peer): skipped")
            return 77
        print("no Targets table in the output")
        return 1
    table = [l for l in lines[lines.index("## Targets") :] if l.startswith("|")]
    header, rows = cells(table[0]), [cells(l) for l in table[2:]]
    if header != ["what", "measured", "target", "met", "rounds met", "per round"]:
        print(f"Targets header is {header}")
        return 1
    problems, timed = [], 0
    for what, measured, target, met, rounds, span in rows:
        if rounds == "-":
            if span != "-":
                problems.append(f"{what}: per round {span!r} without rounds")
            continue
        timed += 1
        m = re.fullmatch(r"([0-9]+) of ([0-9]+)", rounds)
        r = re.fullmatch(NUMBER + r"(.*) \(" + NUMBER + r" - " + NUMBER + r"\)", span)
        v = re.fullmatch(NUMBER + r"(.*)", measured)
        if not (m and r and v):
            problems.append(f"{what}: rounds {rounds!r}, per round {span!r}, "
                            f"measured {measured!r}")
            continue
        k, n = int(m.group(1)), int(m.group(2))
        mid, unit, lo, hi = r.group(1), r.group(2), r.group(3), r.group(4)
        if n != repeats or not 0 <= k <= n:
            problems.append(f"{what}: {rounds} with --repeats {repeats}")
        if "nan" in (lo, mid, hi) or not float(lo) <= float(mid) <= float(hi) \
                or unit != v.group(2):
            problems.append(f"{what}: per round {span!r} (measured {measured!r})")
        if n == 1 and not (lo == mid == hi == v.group(1) and (met == "yes") == (k == 1)):
            problems.append(f"{what}: one round, but measured {measured}, met {met}, "
                            f"rounds met {rounds}, per round {span}")
    if timed == 0 and not problems and skip_if_untimed:
        print("no Targets row timed in rounds (no Embree peer): skipped")
        return 77
    if timed == 0:
        problems.append("no Targets row is timed in rounds")
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
