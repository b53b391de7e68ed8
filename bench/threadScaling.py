#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""bench/threadScaling.py CASE [-n 5] [-umppm BIN ...]

umppmFoam with OMP_NUM_THREADS=1 and 2 on a copy of CASE (an OpenFOAM case
with its mesh and 0/; the case itself is not touched), the two alternating,
n times each; prints per binary the best (minimum) of the n runs of: the
whole run's wall seconds, the set-up ("PPE matrix assembled and factorized
once (s)") and the wall seconds of every stage of the log's "Time by stage"
table, for 1 and 2 threads and their ratio. Several -umppm binaries (e.g. an
older revision) are timed in turn within each repetition, so they see the
same machine. The minimum over runs, because this VM's wall times are noisy
upwards (README, "Speed and threads"); then the median whole-run wall times
and their ratio, and the ratio of each alternating 1/2-thread pair.

Example (the 160^2 cavity of bench/vsOpenFOAM.sh):
  bench/vsOpenFOAM.sh -cases cavity160 -work /tmp/vs
  bench/threadScaling.py /tmp/vs/cavity160/base -n 5
"""
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

STAGE = re.compile(r'    (.+?)\s+([0-9.]+)\s+([0-9.]+)\s+[0-9.]+ %')
SETUP = re.compile(r'factorized once \(([0-9.eE+-]+) s\)')


def run(binary, case, threads):
    for d in os.listdir(case):  # the copy's earlier results, never the user's case
        if d != '0' and re.fullmatch(r'[0-9.eE+-]+', d):
            shutil.rmtree(os.path.join(case, d))
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    t0 = time.monotonic()
    p = subprocess.run([binary], cwd=case, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True)
    wall = time.monotonic() - t0
    if p.returncode != 0:
        sys.exit('%s failed in %s:\n%s' % (binary, case, p.stdout[-2000:]))
    out = {'wall (whole run)': wall}
    for line in p.stdout.splitlines():
        m = STAGE.match(line)
        if m:
            out[m.group(1)] = float(m.group(3))
        m = SETUP.search(line)
        if m:
            out['set-up (solver create)'] = float(m.group(1))
    return out


def main():
    args = sys.argv[1:]
    if not args or args[0].startswith('-'):
        sys.exit(__doc__)
    case, n, bins = args[0], 5, []
    i = 1
    while i < len(args):
        if args[i] == '-n':
            n = int(args[i + 1])
        elif args[i] == '-umppm':
            bins.append(os.path.abspath(args[i + 1]))
        else:
            sys.exit('unknown option %s\n%s' % (args[i], __doc__))
        i += 2
    if not bins:
        bins = [os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'bin', 'umppmFoam')]
    work = tempfile.mkdtemp(prefix='umppm-threads.')
    copy = os.path.join(work, 'case')
    shutil.copytree(case, copy)
    best = {b: {1: {}, 2: {}} for b in bins}
    walls = {b: {1: [], 2: []} for b in bins}
    for _ in range(n):
        for b in bins:
            for t in (1, 2):
                r = run(b, copy, t)
                walls[b][t].append(r['wall (whole run)'])
                for k, v in r.items():
                    best[b][t][k] = min(best[b][t].get(k, v), v)
    shutil.rmtree(work)
    for b in bins:
        print('# %s, best of %d runs each (wall s): 1 thread, 2 threads, ratio' % (b, n))
        for k, v1 in best[b][1].items():
            v2 = best[b][2].get(k, 0.0)
            print('%-36s %8.3f %8.3f %6.2f' % (k, v1, v2, v1 / v2 if v2 > 0 else 0.0))
        w1, w2 = walls[b][1], walls[b][2]
        print('%-36s %8.3f %8.3f %6.2f' % ('wall (whole run), median', statistics.median(w1),
                                          statistics.median(w2), statistics.median(w1) / statistics.median(w2)))
        print('# whole-run ratio of each alternating pair: %s' %
              ' '.join('%.2f' % (a / c) for a, c in zip(w1, w2)))


if __name__ == '__main__':
    main()
