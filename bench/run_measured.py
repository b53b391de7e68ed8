#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# run_measured.py [-o LOG] CMD... -- run a command, print "<wall seconds>
# <peak RSS MiB> <exit status>" of the child on one stdout line (stdlib only:
# resource, subprocess). The command's output goes to LOG (default: nowhere).
import resource, subprocess, sys, time

args = sys.argv[1:]
out = subprocess.DEVNULL
if len(args) > 1 and args[0] == '-o':
    out = open(args[1], 'w')
    args = args[2:]
t0 = time.perf_counter()
rc = subprocess.call(args, stdout=out, stderr=subprocess.STDOUT)
wall = time.perf_counter() - t0
rss = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024.0
print(f"{wall:.3f} {rss:.1f} {rc}")
