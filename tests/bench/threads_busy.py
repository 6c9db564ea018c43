#!/usr/bin/env python3
"""How busy the OpenCL device's threads are while SimSols steps.

Runs `simsols run SCENE --stop-after STEPS` and samples, every 0.2 s, the
CPU time of each of its threads from /proc/PID/task/TID/stat (user + system
ticks). The window starts once the run has stepped for --skip seconds (the
kernel build and set-up are past) and ends at the last sample before exit.
Prints per thread its role and its busy share of the window, and the
share of the device's worker threads together: every thread but the main
one, which enqueues the work (PoCL's pthread device runs one worker per
core; the process starts no other threads when headless).

  tests/bench/threads_busy.py [--simsols BIN] [--skip S] [--precision P] SCENE STEPS

Linux only (reads /proc). Example, the 2.38 mm shear work:
  assets/crosscheck/liggghts/scene_2.38mm.sh /tmp/s.toml
  tests/bench/threads_busy.py /tmp/s.toml 60000
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time


def thread_times(pid):
    """{tid: (name, ticks)} of the process's threads now."""
    out = {}
    base = f"/proc/{pid}/task"
    for tid in os.listdir(base):
        try:
            with open(f"{base}/{tid}/stat") as f:
                text = f.read()
        except OSError:
            continue
        name = text[text.index("(") + 1:text.rindex(")")]
        fields = text[text.rindex(")") + 2:].split()
        out[tid] = (name, int(fields[11]) + int(fields[12]))  # utime + stime
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene")
    ap.add_argument("steps", type=int)
    ap.add_argument("--simsols", default="build/release/app/simsols")
    ap.add_argument("--skip", type=float, default=3.0, help="seconds before the window (default 3)")
    ap.add_argument("--precision", default="float")
    a = ap.parse_args()
    hz = os.sysconf("SC_CLK_TCK")
    with tempfile.TemporaryDirectory() as out:
        cmd = [a.simsols, "run", a.scene, "--out", out, "--precision", a.precision,
               "--stop-after", str(a.steps), "-q"]
        p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL)
        pid = p.pid
        t0 = time.monotonic()
        start = end = None
        first, last = {}, {}  # per thread: ticks at its first and last sample in the window
        while p.poll() is None:
            time.sleep(0.2)
            try:
                now, sample = time.monotonic(), thread_times(p.pid)
            except OSError:
                break
            if now - t0 < a.skip or len(sample) < len(last):
                continue  # before the window, or threads already leaving (the end)
            start = start or now
            end = now
            for tid, v in sample.items():
                first.setdefault(tid, v)
                last[tid] = v
        if p.wait() != 0:
            sys.exit(f"threads_busy: {' '.join(cmd)} failed ({p.returncode})")
    if not start or end - start < 1:
        sys.exit("threads_busy: the run was too short for a window; raise STEPS")
    span = end - start
    print(f"window {span:.1f} s of the run ({a.steps} steps, {a.precision}), {os.cpu_count()} cores")
    workers = []
    for tid in sorted(last, key=int):
        name, ticks = last[tid]
        busy = (ticks - first[tid][1]) / hz / span
        role = "host (enqueues)" if int(tid) == pid else "device worker"
        print(f"  thread {tid:>8} {role:<16} busy {100 * busy:5.1f} %")
        if int(tid) != pid:
            workers.append(busy)
    if workers:
        print(f"device threads: {len(workers)}, busy {100 * sum(workers) / len(workers):.1f} % "
              "of the window on average")


if __name__ == "__main__":
    main()
