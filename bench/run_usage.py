#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# run_usage.py -o LOG [-first REGEX] CMD... -- run a command (the sibling of
# run_measured.py with CPU time and a start-up mark), its stdout and stderr
# into LOG, and print one stdout line:
#   <wall s> <CPU s> <peak RSS MiB> <first s> <exit status>
# wall: from just before the launch to the end of the wait (perf_counter).
# CPU: user + sys of the command and of all its descendants that were
#   waited for: the rusage of os.wait4 on the command (what
#   getrusage(RUSAGE_CHILDREN) gives, without what this interpreter's own
#   launcher, e.g. a pyenv shim, ran before it); for mpirun that is mpirun
#   and its ranks, which it reaps, so the sum over the processes.
# peak RSS: the largest single process's peak (for mpirun: the max over
#   the ranks and mpirun, not their sum): ru_maxrss of the same rusage,
#   except that it cannot be below this interpreter's own peak (the kernel
#   keeps the high-water mark of the image replaced at exec, here the
#   forked interpreter); when it is not above that, the VmHWM of the
#   command's processes sampled from /proc every 20 ms is used instead.
# first: wall seconds from the launch to the first output line matching
#   REGEX (default '^Time = '), '-' if none. The output is read through a
#   pipe as it comes, so a solver whose stdout is fully buffered must be
#   line-buffered (stdbuf -oL) for 'first' to mean anything.
# stdlib only (os, re, subprocess, threading, time).
import os, re, subprocess, sys, threading, time


def status(pid):
    """(Name, VmHWM KiB) of a process, None if gone or not readable."""
    try:
        with open(f'/proc/{pid}/status') as f:
            name, hwm = '', 0
            for line in f:
                if line.startswith('Name:'):
                    name = line.split()[1]
                elif line.startswith('VmHWM:'):
                    hwm = int(line.split()[1])
            return name, hwm
    except (OSError, ValueError, IndexError):
        return None


def descendants(pid):
    out, todo = [], [pid]
    while todo:
        q = todo.pop()
        out.append(q)
        try:
            for t in os.listdir(f'/proc/{q}/task'):
                with open(f'/proc/{q}/task/{t}/children') as f:
                    todo.extend(int(c) for c in f.read().split())
        except (OSError, ValueError):
            pass
    return out


args = sys.argv[1:]
log, first_re = None, re.compile(rb'^Time = ')
while args and args[0] in ('-o', '-first'):
    if len(args) < 3:
        sys.exit('usage: run_usage.py -o LOG [-first REGEX] CMD...')
    if args[0] == '-o':
        log = args[1]
    else:
        first_re = re.compile(args[1].encode())
    args = args[2:]
if log is None or not args:
    sys.exit('usage: run_usage.py -o LOG [-first REGEX] CMD...')
me = status('self')
first, latest, done = None, {}, threading.Event()


def sample(root):
    while not done.is_set():
        for q in descendants(root):
            s = status(q)
            # HWM only grows within one image: keep the latest (a zombie,
            # exited but not yet reaped, has no VmHWM: keep what it had)
            if s is not None and s[1] > 0:
                latest[q] = s
        done.wait(0.02)


with open(log, 'wb') as out:
    t0 = time.perf_counter()
    try:
        p = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    except OSError as e:
        out.write(f'run_usage.py: cannot run {args[0]}: {e}\n'.encode())
        print('0 0 0 - 127')
        sys.exit(0)
    th = threading.Thread(target=sample, args=(p.pid,), daemon=True)
    th.start()
    for line in p.stdout:
        if first is None and first_re.search(line):
            first = time.perf_counter() - t0
        out.write(line)
    _, st, ru = os.wait4(p.pid, 0)
    wall = time.perf_counter() - t0
    p.returncode = rc = os.waitstatus_to_exitcode(st)
    done.set()
    th.join()
rss = ru.ru_maxrss  # KiB
floor = me[1] if me else 0
if rss <= floor + 1024:
    # a sample still of the forked interpreter (before its exec) has its name
    polled = [h for n, h in latest.values() if not me or n != me[0]]
    if polled:
        rss = max(polled)
first_s = '-' if first is None else f'{first:.3f}'
print(f'{wall:.3f} {ru.ru_utime + ru.ru_stime:.3f} {rss / 1024.0:.1f} {first_s} {rc}')
