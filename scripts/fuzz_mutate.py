#!/usr/bin/env python3
"""Black-box mutation fuzzing of `gvd compute` (issue 15, docs/FUZZING.md).

Mutates the repository's scenes (examples/scenes/*.json, crates/gvd/tests/data/**.json):
numbers scaled by 1e±150 / 1e±300 or translated by 1e15, epsilon made tiny, fields
deleted, duplicated or given another type, sites duplicated, texts cut; and picks odd
options (--engine, --max-box, --max-boxes, --threads, --mode). Each mutant runs under
`gvd compute --timeout T` with a wall-clock kill at 2T + 5 s and a memory limit, and is
classified:

  refusal  exit 2, a message, no output file
  result   exit 0 with the output file (then `gvd verify` on it, for the record)
  hang     killed at the wall-clock limit
  crash    a signal (abort, out of memory), a panic, exit 101, any other exit code,
           a refusal that left an output, a message longer than 2000 characters

    scripts/fuzz_mutate.py [--seconds S | --runs N] [--seed K] [--gvd target/release/gvd]
                           [--keep DIR]

Hangs and crashes are written to --keep (default: a temporary folder, printed) as
reproducers with the command line, and so are the scenes on which `gvd verify` hung
or crashed, and the results that failed it (scene, diagram `*.out.json`, command). Exit 1 when any compute run hung or crashed, or verify crashed (a slow
verify is reported, not failed: it is bounded by its sample cap, docs/FUZZING.md).
"""

import argparse
import glob
import json
import os
import random
import resource
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCALES = [1e150, 1e-150, 1e300, 1e-300]
HOSTILE = [0.0, -0.0, 1e308, -1e308, 5e-324, 1e-300, 1e300, 1e15, -1.0, 1e-15]
MAX_MESSAGE = 2000


def seeds():
    paths = glob.glob(os.path.join(ROOT, "examples/scenes/*.json"))
    paths += glob.glob(os.path.join(ROOT, "crates/gvd/tests/data/**/*.json"), recursive=True)
    out = []
    for p in sorted(paths):
        try:
            with open(p) as f:
                v = json.load(f)
        except (OSError, ValueError):
            continue
        # small scenes only: the fuzzing is about odd values, not size
        if isinstance(v, dict) and "sites" in v and len(json.dumps(v)) < 40_000:
            out.append((os.path.relpath(p, ROOT), v))
    return out


def numbers(v, path=()):
    """Paths to every number in v."""
    if isinstance(v, bool):
        return
    if isinstance(v, (int, float)):
        yield path
    elif isinstance(v, list):
        for i, e in enumerate(v):
            yield from numbers(e, path + (i,))
    elif isinstance(v, dict):
        for k, e in v.items():
            yield from numbers(e, path + (k,))


def get(v, path):
    for k in path:
        v = v[k]
    return v


def put(v, path, x):
    get(v, path[:-1])[path[-1]] = x


def scale_all(v, f, rng):
    """Every number of the scene's geometry times f (or translated, for 1e15)."""
    for p in list(numbers(v)):
        if "sites" in p and any(k in ("degree", "p", "weights", "knots") for k in p if isinstance(k, str)):
            continue
        x = get(v, p)
        put(v, p, x + f if f == 1e15 else x * f)


def mutate(v, rng):
    what = rng.randrange(9)
    nums = list(numbers(v))
    sites = v.get("sites") if isinstance(v.get("sites"), list) else []
    if what == 0:
        scale_all(v, rng.choice(SCALES + [1e15]), rng)
    elif what == 1:
        v["epsilon"] = rng.choice([1e-15, 1e-17, 1e-300, 5e-324, 0.0, -1e-3, 1e300])
    elif what == 2 and nums:
        p = rng.choice(nums)
        x = get(v, p)
        put(v, p, rng.choice([x * rng.choice(SCALES), rng.choice(HOSTILE)]))
    elif what == 3 and sites:
        s = rng.choice(sites)
        if isinstance(s, dict) and s:
            del s[rng.choice(list(s))]
    elif what == 4 and sites:
        sites.append(json.loads(json.dumps(rng.choice(sites))))
    elif what == 5 and sites:
        s = rng.choice(sites)
        if isinstance(s, dict) and s:
            k = rng.choice(list(s))
            s[k] = rng.choice([None, "x", [], {}, [s[k], s[k]], -1])
    elif what == 6:
        k = rng.choice(["domain", "epsilon", "mode", "sites"])
        v.pop(k, None) if rng.random() < 0.5 else v.__setitem__(k, rng.choice([None, [], "x", 0]))
    elif what == 7 and sites:
        # a site moved by one ulp-ish onto another: nearly coincident sites
        s = json.loads(json.dumps(rng.choice(sites)))
        for p in list(numbers(s))[:1]:
            put(s, p, get(s, p) * (1 + 2e-16))
        sites.append(s)
    else:
        v["domain"] = rng.choice([[-1e15, -1e15, 1e15, 1e15], [-1e307, -1e307, 1e307, 1e307],
                                  [0, 0, 0, 0], [1, 1, -1, -1], [-1e-300, -1e-300, 1e-300, 1e-300]])


def text_of(v, rng):
    t = json.dumps(v)
    r = rng.random()
    if r < 0.05:
        t = t[: rng.randrange(len(t) + 1)]
    elif r < 0.10:
        t = t.replace("0.", "1e400", 1)
    return t


def options(rng):
    o = []
    if rng.random() < 0.5:
        o += ["--engine", rng.choice(["auto", "subdivision", "incremental", "freeform"])]
    if rng.random() < 0.2:
        o += ["--max-box", rng.choice(["0.1", "1e-6", "1e-300", "1e300"])]
    if rng.random() < 0.15:
        o += ["--max-boxes", rng.choice(["1", "100", "18446744073709551615"])]
    if rng.random() < 0.1:
        o += ["--threads", rng.choice(["1", "2", "256"])]
    if rng.random() < 0.15:
        o += ["--mode", rng.choice(["voronoi", "complex", "medial_axis"])]
    if rng.random() < 0.1:
        o += ["--bisectors"]
    return o


def limit_memory():
    gb = 4 << 30
    resource.setrlimit(resource.RLIMIT_AS, (gb, gb))


def run_one(gvd, work, text, opts, timeout):
    scene = os.path.join(work, "scene.json")
    out = os.path.join(work, "out.json")
    with open(scene, "w") as f:
        f.write(text)
    if os.path.exists(out):
        os.remove(out)
    cmd = [gvd, "compute", scene, "--json", out, "--timeout", str(timeout)] + opts
    t0 = time.time()
    try:
        p = subprocess.run(cmd, capture_output=True, timeout=2 * timeout + 5,
                           preexec_fn=limit_memory, stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired:
        return "hang", time.time() - t0, "killed at the wall-clock limit", cmd
    dt = time.time() - t0
    err = p.stderr.decode(errors="replace")
    wrote = os.path.exists(out)
    if p.returncode < 0 or p.returncode == 101 or "panicked" in err:
        return "crash", dt, err[-500:] or f"signal {-p.returncode}", cmd
    if len(err) > MAX_MESSAGE:
        return "crash", dt, f"a message of {len(err)} characters", cmd
    if p.returncode == 0 and wrote:
        # the diagram is checked in the mode it was computed in
        mode = opts[opts.index("--mode"):][:2] if "--mode" in opts else []
        try:
            v = subprocess.run([gvd, "verify", scene, out, "--grid", "64"] + mode, capture_output=True,
                               timeout=2 * timeout + 5, stdin=subprocess.DEVNULL,
                               preexec_fn=limit_memory)
        except subprocess.TimeoutExpired:
            return "result", dt, "VERIFY-HANG: gvd verify killed at the wall-clock limit", cmd
        last = v.stdout.decode(errors="replace").strip().splitlines()[-1:] or [""]
        if v.returncode not in (0, 1, 2) or "panicked" in v.stderr.decode(errors="replace"):
            return "result", dt, f"VERIFY-CRASH: exit {v.returncode}", cmd
        return "result", dt, last[0][:120], cmd
    if p.returncode == 2 and not wrote and err.strip():
        return "refusal", dt, err.strip()[:160], cmd
    return "crash", dt, f"exit {p.returncode}, output written: {wrote}: {err[:300]}", cmd


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seconds", type=float, default=60)
    ap.add_argument("--runs", type=int, default=0, help="a number of runs instead of --seconds")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=5, help="--timeout given to gvd compute")
    ap.add_argument("--gvd", default=os.path.join(ROOT, "target/release/gvd"))
    ap.add_argument("--keep", default=None)
    a = ap.parse_args()
    rng = random.Random(a.seed)
    base = seeds()
    work = tempfile.mkdtemp(prefix="gvd-fuzz-")
    keep = a.keep or tempfile.mkdtemp(prefix="gvd-fuzz-found-")
    os.makedirs(keep, exist_ok=True)
    counts = {"refusal": 0, "result": 0, "hang": 0, "crash": 0}
    verify_fail = verify_bad = verify_crash = 0
    slowest = (0.0, "")
    start = time.time()
    n = 0
    while (n < a.runs) if a.runs else (time.time() - start < a.seconds):
        name, v = rng.choice(base)
        v = json.loads(json.dumps(v))
        for _ in range(rng.randrange(1, 4)):
            try:
                mutate(v, rng)
            except (TypeError, KeyError, IndexError, AttributeError, OverflowError):
                pass
        try:
            text = text_of(v, rng)
        except ValueError:
            continue
        opts = options(rng)
        kind, dt, msg, cmd = run_one(a.gvd, work, text, opts, a.timeout)
        n += 1
        counts[kind] += 1
        if kind == "result" and "FAIL" in msg:
            # a result gvd verify failed: kept with its diagram, to triage
            verify_fail += 1
            stem = os.path.join(keep, f"verify-fail-{verify_fail:03}")
            with open(stem + ".json", "w") as f:
                f.write(text)
            shutil.copyfile(os.path.join(work, "out.json"), stem + ".out.json")
            with open(stem + ".txt", "w") as f:
                f.write(f"from {name}\n{' '.join(cmd[2:])}\n{msg}\n")
            print(f"VERIFY-FAIL from {name} {' '.join(opts)}: {msg}", flush=True)
        if kind == "result" and msg.startswith("VERIFY-CRASH"):
            verify_crash += 1
        if kind == "result" and msg.startswith("VERIFY-"):
            # gvd verify hung or crashed on a diagram gvd compute wrote: kept, and a failure
            verify_bad += 1
            with open(os.path.join(keep, f"verify-{verify_bad:03}.json"), "w") as f:
                f.write(text)
            with open(os.path.join(keep, f"verify-{verify_bad:03}.txt"), "w") as f:
                f.write(f"from {name}\n{' '.join(cmd[2:])}\n{msg}\n")
            print(f"{msg.split(':')[0]} from {name} {' '.join(opts)}", flush=True)
        if dt > slowest[0]:
            slowest = (dt, name)
        if kind in ("hang", "crash"):
            k = counts["hang"] + counts["crash"]
            with open(os.path.join(keep, f"{kind}-{k:03}.json"), "w") as f:
                f.write(text)
            with open(os.path.join(keep, f"{kind}-{k:03}.txt"), "w") as f:
                f.write(f"from {name}\n{' '.join(cmd[2:])}\n{dt:.1f} s\n{msg}\n")
            print(f"{kind.upper()} from {name} {' '.join(opts)} ({dt:.1f} s): {msg[:200]}", flush=True)
    shutil.rmtree(work, ignore_errors=True)
    print(f"{n} runs in {time.time() - start:.0f} s from {len(base)} scenes (seed {a.seed}): "
          + ", ".join(f"{c} {k}" for k, c in counts.items())
          + f"; {verify_fail} results failed gvd verify, {verify_bad} hung or crashed it; slowest {slowest[0]:.1f} s ({slowest[1]})")
    if counts["hang"] or counts["crash"] or verify_crash:
        print(f"reproducers in {keep}")
        return 1
    if not a.keep:
        shutil.rmtree(keep, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
