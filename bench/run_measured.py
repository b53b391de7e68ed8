#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# run_measured.py CMD... -- run a command, print "<wall seconds> <peak RSS MiB>"
# of the child on stderr-free stdout line (stdlib only: resource, subprocess).
import resource, subprocess, sys, time

t0 = time.perf_counter()
rc = subprocess.call(sys.argv[1:], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
wall = time.perf_counter() - t0
rss = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024.0
print(f"{wall:.3f} {rss:.1f} {rc}")
