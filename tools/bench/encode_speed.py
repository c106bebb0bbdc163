#!/usr/bin/python3
"""`srcodec encode` of an older commit against the current one, side by side on the same meshes.

For each mesh, N runs; each run encodes with both binaries, one after the other, the order alternating
from run to run (old first in run 1, new first in run 2, ...) so that neither side always gets the
warmer or the quieter slot. Each encode runs under `/usr/bin/time -v`: wall time, user + system CPU,
peak resident memory. Per mesh: the median wall time of each side, the median of the per-run ratios
old / new (a ratio of two encodes made seconds apart, which the load of a shared machine moves less
than it moves either time), the largest peak memory, whether each side wrote the same bytes in every
run, and each side's file: its bytes and PSNR (decoded to the finest level by its own binary, measured
against the input by the NEW binary's `srcodec compare`, the same instrument for both). Prints a
Markdown table and a summary (the median ratio over the meshes, the mesh with the smallest ratio);
--json writes every run.

The old side (and --new REV) is built from `git archive REV` in CACHE/<commit>/ (Release, no tests;
CACHE defaults to ~/.cache/srcodec-bench) and reused from there by later runs. Without --new or
--new-binary the new side is this checkout's build/tools/srcodec.

usage: /usr/bin/python3 tools/bench/encode_speed.py --old REV [--new REV | --new-binary PATH]
           [--runs N] [--cache DIR] [--json OUT] MESH... [-- ENCODE OPTION...]
Everything after `--` is passed to every `srcodec encode` (both sides), e.g. `-- --levels 3`.
(docs/encoder_speed.md)
"""
import argparse
import fcntl
import hashlib
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DEFAULT_CACHE = os.path.join(os.path.expanduser("~"), ".cache", "srcodec-bench")
PROG = os.path.basename(sys.argv[0])


class Error(RuntimeError):
    """A failure that ends the benchmark: its text is what to tell the user."""


def say(text):
    """Progress and notes go to stderr, so that stdout holds only the Markdown."""
    print(text, file=sys.stderr, flush=True)


def git(*args):
    p = subprocess.run(["git", "-C", ROOT] + list(args), capture_output=True, text=True)
    if p.returncode != 0:
        raise Error(f"git {' '.join(args)}: {p.stderr.strip() or 'exit %d' % p.returncode}")
    return p.stdout.strip()


def resolve(rev):
    """The full hash of commit `rev` in this repository; Error when there is none."""
    p = subprocess.run(["git", "-C", ROOT, "rev-parse", "--verify", "--quiet", rev + "^{commit}"],
                       capture_output=True, text=True)
    if p.returncode != 0:
        raise Error(f"no commit '{rev}' in {ROOT}")
    return p.stdout.strip()


def describe(commit):
    """'c1beed993ee9 (2026-12-06) subject' of a commit, to say in the output which code a side is."""
    text = git("log", "-1", "--format=%h (%cs) %s", "--abbrev=12", commit)
    return text if len(text) <= 90 else text[:87] + "..."


def tail(path, lines=30):
    with open(path, errors="replace") as f:
        return "".join(f.readlines()[-lines:])


def build(commit, cache):
    """The srcodec binary of `commit`, built in CACHE/<commit>/ unless a finished build is there already.
    Returns (path, reused). A lock file keeps two benchmarks from building the same commit at once."""
    where = os.path.join(cache, commit)
    binary = os.path.join(where, "build", "tools", "srcodec")
    done = os.path.join(where, "BUILT")  # written last: an interrupted build is not taken for a finished one
    os.makedirs(cache, exist_ok=True)
    with open(os.path.join(cache, commit + ".lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if os.path.exists(done) and os.access(binary, os.X_OK):
            return binary, True
        os.makedirs(where, exist_ok=True)
        src = os.path.join(where, "src")
        log = os.path.join(where, "build.log")
        if not os.path.isdir(src):
            # The commit's tracked files only (no worktree to clean up); unpacked aside, then renamed, so
            # that src/ is never half there.
            part = src + ".part"
            shutil.rmtree(part, ignore_errors=True)
            os.makedirs(part)
            archive = subprocess.Popen(["git", "-C", ROOT, "archive", commit], stdout=subprocess.PIPE)
            untar = subprocess.run(["tar", "-x", "-C", part], stdin=archive.stdout)
            archive.stdout.close()
            if archive.wait() != 0 or untar.returncode != 0:
                raise Error(f"git archive {commit} | tar -x into {part} failed")
            os.rename(part, src)
        say(f"{PROG}: building {describe(commit)} in {where} (6-10 min on 2 cores; log: {log})")
        start = time.monotonic()
        with open(log, "a") as out:
            for step in (["cmake", "-S", src, "-B", os.path.join(where, "build"), "-DCMAKE_BUILD_TYPE=Release",
                          "-DSRCODEC_BUILD_TESTS=OFF"],
                         ["cmake", "--build", os.path.join(where, "build"), "--target", "srcodec", "-j2"]):
                out.write("$ " + " ".join(step) + "\n")
                out.flush()
                if subprocess.run(step, stdout=out, stderr=subprocess.STDOUT).returncode != 0:
                    raise Error(f"building {commit} failed ({' '.join(step[:2])}); the end of {log}:\n"
                                + tail(log))
        if not os.access(binary, os.X_OK):
            raise Error(f"building {commit} made no {binary}; the end of {log}:\n" + tail(log))
        open(done, "w").close()
        say(f"{PROG}: built {commit[:12]} in {time.monotonic() - start:.0f} s")
        return binary, False


def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def timed_encode(binary, mesh, out, extra, scratch):
    """One `srcodec encode MESH -o OUT EXTRA` under /usr/bin/time -v. Returns a dict: ok, wall_s, cpu_s (user +
    system), peak_mb, load (the 1-minute load average just before), and on success bytes and sha256, on
    failure error (the last line srcodec printed)."""
    times = os.path.join(scratch, "time.txt")
    errors = os.path.join(scratch, "stderr.txt")
    load = os.getloadavg()[0]
    with open(errors, "w") as err:
        p = subprocess.run(["/usr/bin/time", "-v", "-o", times, binary, "encode", mesh, "-o", out] + extra,
                           stdout=subprocess.DEVNULL, stderr=err)
    t = open(times).read()
    run = {"load": round(load, 2)}

    def field(name):
        m = re.search(re.escape(name) + r": (.+)", t)
        return m.group(1).strip() if m else None

    wall = field("Elapsed (wall clock) time (h:mm:ss or m:ss)")
    if wall is not None:
        run["wall_s"] = sum(float(x) * 60 ** i for i, x in enumerate(reversed(wall.split(":"))))
        run["cpu_s"] = round(float(field("User time (seconds)")) + float(field("System time (seconds)")), 2)
        run["peak_mb"] = round(int(field("Maximum resident set size (kbytes)")) / 1024, 1)
    run["ok"] = p.returncode == 0 and os.path.exists(out)
    if run["ok"]:
        run["bytes"] = os.path.getsize(out)
        run["sha256"] = sha256(out)
    else:
        lines = open(errors, errors="replace").read().strip().splitlines()
        # time -v appends "Command exited with non-zero status N" to its own file, not to stderr
        run["error"] = lines[-1] if lines else f"exit {p.returncode}"
    return run


def measure_file(side_binary, compare_binary, mesh, srm, scratch):
    """(PSNR of `srm` decoded to its finest level by its own side's binary, measured against `mesh` by the
    new side's compare, None) or (None, what failed)."""
    decoded = os.path.join(scratch, "decoded.obj")
    p = subprocess.run([side_binary, "decode", srm, "-o", decoded], capture_output=True, text=True)
    if p.returncode != 0:
        return None, "decode: " + ((p.stderr.strip().splitlines() or [f"exit {p.returncode}"])[-1])
    p = subprocess.run([compare_binary, "compare", mesh, decoded, "--json"], capture_output=True, text=True)
    os.remove(decoded)
    if p.returncode != 0:
        return None, "compare: " + ((p.stderr.strip().splitlines() or [f"exit {p.returncode}"])[-1])
    return json.loads(p.stdout)["psnr"], None


def bench_mesh(mesh, sides, runs, extra, compare_binary, scratch):
    """Both sides' runs on one mesh, alternated; returns the mesh's record (every run, and the summary)."""
    name = os.path.basename(mesh)
    record = {"mesh": mesh, "runs": [], "sides": {}}
    failed = {}  # side -> error: a side that failed once is not run again on this mesh
    for i in range(runs):
        order = ["old", "new"] if i % 2 == 0 else ["new", "old"]
        entry = {"run": i + 1, "order": order}
        for side in order:
            if side in failed:
                continue
            out = os.path.join(scratch, f"{side}.run{i + 1}.srm")
            r = timed_encode(sides[side]["binary"], mesh, out, extra, scratch)
            entry[side] = r
            if not r["ok"]:
                failed[side] = r["error"]
                say(f"{PROG}: {name}: the {side} side failed to encode: {r['error']}")
        if "old" in entry and "new" in entry and entry["old"]["ok"] and entry["new"]["ok"]:
            # /usr/bin/time's wall clock has 10 ms steps: a floor keeps a tiny mesh from dividing by zero
            entry["ratio"] = entry["old"]["wall_s"] / max(entry["new"]["wall_s"], 0.01)
            # CPU time moves less than wall time with other jobs on the machine; a second view of the ratio
            entry["cpu_ratio"] = entry["old"]["cpu_s"] / max(entry["new"]["cpu_s"], 0.01)
        record["runs"].append(entry)
        say(f"{PROG}: {name} run {i + 1}/{runs}: " + ", ".join(
            f"{s} {entry[s]['wall_s']:.2f} s" if s in entry and entry[s]["ok"] else f"{s} failed"
            for s in ("old", "new")) + f" (load {os.getloadavg()[0]:.2f})")

    for side in ("old", "new"):
        done = [e[side] for e in record["runs"] if side in e and e[side]["ok"]]
        s = {"ok": side not in failed}
        if not s["ok"]:
            s["error"] = failed[side]
        if done:
            hashes = sorted({r["sha256"] for r in done})
            s.update(median_wall_s=statistics.median(r["wall_s"] for r in done),
                     median_cpu_s=statistics.median(r["cpu_s"] for r in done),
                     max_peak_mb=max(r["peak_mb"] for r in done),
                     bytes=done[0]["bytes"], sha256=done[0]["sha256"],
                     # one run shows nothing about determinism: None, not True
                     deterministic=len(hashes) == 1 if len(done) > 1 else None, distinct_files=len(hashes))
            if len(hashes) > 1:
                say(f"{PROG}: {name}: the {side} side is NOT deterministic: {len(hashes)} different files in "
                    f"{len(done)} runs (sizes {sorted({r['bytes'] for r in done})})")
            # The first run's file: with a deterministic side every run's file is this one.
            first = next(e for e in record["runs"] if side in e and e[side]["ok"])["run"]
            psnr, why = measure_file(sides[side]["binary"], compare_binary, mesh,
                                     os.path.join(scratch, f"{side}.run{first}.srm"), scratch)
            s["psnr"] = psnr
            if why:
                s["measure_error"] = why
                say(f"{PROG}: {name}: measuring the {side} side's file failed: {why}")
        record["sides"][side] = s
    ratios = [e["ratio"] for e in record["runs"] if "ratio" in e]
    if ratios:
        record["median_ratio"] = statistics.median(ratios)
        record["median_cpu_ratio"] = statistics.median(e["cpu_ratio"] for e in record["runs"] if "cpu_ratio" in e)
    for f in os.listdir(scratch):
        os.remove(os.path.join(scratch, f))
    return record


def fmt(value, spec, missing="-"):
    return missing if value is None else format(value, spec)


def table(records):
    lines = ["| mesh | old median s | new median s | ratio old/new | CPU s old/new | peak MB old/new "
             "| bytes old/new | PSNR dB old/new | same file |",
             "|---|---|---|---|---|---|---|---|---|"]
    for rec in records:
        o, n = rec["sides"]["old"], rec["sides"]["new"]
        name = os.path.basename(rec["mesh"])
        notes = [f"{side} FAILED" for side, s in (("old", o), ("new", n)) if not s["ok"]]
        notes += [f"{side} not deterministic ({s['distinct_files']} files)" for side, s in (("old", o), ("new", n))
                  if s.get("deterministic") is False]
        if notes:
            name += " (" + "; ".join(notes) + ")"
        ratio = rec.get("median_ratio")
        runs = sum(1 for e in rec["runs"] if "ratio" in e)
        same = "yes" if o.get("sha256") and o.get("sha256") == n.get("sha256") else (
            "no" if o.get("sha256") and n.get("sha256") else "-")
        ratio = f"{ratio:.3f}x ({runs} runs)" if ratio is not None else "-"
        lines.append(
            f"| {name} | {fmt(o.get('median_wall_s'), '.2f')} | {fmt(n.get('median_wall_s'), '.2f')} "
            f"| {ratio} | {fmt(o.get('median_cpu_s'), '.2f')} / "
            f"{fmt(n.get('median_cpu_s'), '.2f')} | {fmt(o.get('max_peak_mb'), '.0f')} / "
            f"{fmt(n.get('max_peak_mb'), '.0f')} | {fmt(o.get('bytes'), 'd')} / {fmt(n.get('bytes'), 'd')} "
            f"| {fmt(o.get('psnr'), '.2f')} / {fmt(n.get('psnr'), '.2f')} | {same} |")
    # What failed, under the table: the table only marks it
    failures = [f"- {os.path.basename(rec['mesh'])}, {side} side, {what} failed: {rec['sides'][side][key]}"
                for rec in records for side in ("old", "new")
                for key, what in (("error", "encode"), ("measure_error", "measuring the file"))
                if key in rec["sides"][side]]
    return "\n".join(lines + ([""] + failures if failures else []))


def summary(records):
    rated = [r for r in records if "median_ratio" in r]
    if not rated:
        return "No mesh encoded on both sides: no ratio."
    worst = min(rated, key=lambda r: r["median_ratio"])
    skipped = len(records) - len(rated)
    return (f"Median ratio old/new over {len(rated)} meshes: {statistics.median(r['median_ratio'] for r in rated):.3f}x; "
            f"smallest: {os.path.basename(worst['mesh'])} {worst['median_ratio']:.3f}x; "
            f"CPU time (user + system) old/new: median {statistics.median(r['median_cpu_ratio'] for r in rated):.3f}x"
            + (f"; {skipped} mesh(es) without a ratio (a side failed)" if skipped else "") + ".")


def parse(argv):
    # Everything after the first `--` goes to `srcodec encode` untouched (its options start with '-' too).
    extra = []
    if "--" in argv:
        k = argv.index("--")
        argv, extra = argv[:k], argv[k + 1:]
    ap = argparse.ArgumentParser(
        prog=PROG, description="Encode speed of an older srcodec commit against the current one, side by side.",
        epilog="Everything after `--` is passed to every `srcodec encode`, e.g. `MESH... -- --levels 3`.")
    ap.add_argument("--old", required=True, metavar="REV", help="the older commit (any git revision)")
    new = ap.add_mutually_exclusive_group()
    new.add_argument("--new", metavar="REV", help="build this commit for the new side")
    new.add_argument("--new-binary", metavar="PATH", help="this srcodec binary is the new side")
    ap.add_argument("--runs", type=int, default=3, help="runs per mesh, each encoding with both (default 3)")
    ap.add_argument("--cache", default=DEFAULT_CACHE, help=f"where builds are kept by commit (default {DEFAULT_CACHE})")
    ap.add_argument("--json", metavar="OUT", help="write every run as JSON here")
    ap.add_argument("meshes", nargs="+", metavar="MESH")
    args = ap.parse_args(argv)
    if args.runs < 1:
        ap.error("--runs must be at least 1")
    args.extra = extra
    return args


def working_tree_side():
    """The new side by default: this checkout's build/tools/srcodec, described by its HEAD (and whether the
    tree has changes the build may or may not include)."""
    binary = os.path.join(ROOT, "build", "tools", "srcodec")
    if not os.access(binary, os.X_OK):
        raise Error(f"no {binary}: build this checkout (cmake --build build --target srcodec), "
                    "or give --new REV or --new-binary PATH")
    dirty = " + uncommitted changes" if git("status", "--porcelain", "--untracked-files=no") else ""
    return {"binary": binary, "commit": git("rev-parse", "HEAD"),
            "label": f"this checkout's build of {describe('HEAD')}{dirty}"}


def binary_note(path):
    st = os.stat(path)
    return f"{path} (built {time.strftime('%Y-%m-%d %H:%M', time.gmtime(st.st_mtime))} UTC, sha256 {sha256(path)[:12]})"


def main(argv):
    args = parse(argv)
    for mesh in args.meshes:
        if not os.path.isfile(mesh):
            raise Error(f"no mesh file {mesh}")
    cache = os.path.abspath(os.path.expanduser(args.cache))
    old_commit = resolve(args.old)  # resolve both revisions before a build of minutes
    new_commit = resolve(args.new) if args.new else None

    sides = {}
    # A new side that needs no build is checked first: a wrong path should not wait for a build of minutes.
    if args.new_binary:
        if not os.access(args.new_binary, os.X_OK):
            raise Error(f"--new-binary {args.new_binary}: not an executable file")
        sides["new"] = {"binary": os.path.abspath(args.new_binary), "commit": None, "label": "the given binary"}
    elif not new_commit:
        sides["new"] = working_tree_side()
    binary, reused = build(old_commit, cache)
    sides["old"] = {"binary": binary, "commit": old_commit, "rev": args.old,
                    "label": f"{describe(old_commit)}, {'cached' if reused else 'built'} build"}
    if new_commit:
        binary, reused = build(new_commit, cache)
        sides["new"] = {"binary": binary, "commit": new_commit, "rev": args.new,
                        "label": f"{describe(new_commit)}, {'cached' if reused else 'built'} build"}
    sides = {"old": sides["old"], "new": sides["new"]}
    for s in sides.values():
        s["note"] = binary_note(s["binary"])

    start_load = os.getloadavg()
    records = []
    with tempfile.TemporaryDirectory(prefix="encode_speed.") as scratch:
        for mesh in args.meshes:
            records.append(bench_mesh(os.path.abspath(mesh), sides, args.runs, args.extra,
                                      sides["new"]["binary"], scratch))
    end_load = os.getloadavg()
    loads = [r[s]["load"] for rec in records for r in rec["runs"] for s in ("old", "new") if s in r]

    extra = " ".join(args.extra) if args.extra else "(none)"
    print(f"- old: {sides['old']['label']}: {sides['old']['note']}")
    print(f"- new: {sides['new']['label']}: {sides['new']['note']}")
    load = f"{min(loads):.2f}-{max(loads):.2f}" if loads else "-"
    print(f"- {args.runs} runs per mesh, alternated (run 1 old first); encode options: {extra}; "
          f"{os.cpu_count()} cores, 1-minute load average before the encodes {load}")
    print("- ratio: the median over the runs of old wall time / new wall time; peak MB: the largest over the runs")
    print(f"- PSNR: each side's file decoded by its own binary, measured by the new binary's `compare`")
    print()
    print(table(records))
    print()
    print(summary(records))

    if args.json:
        with open(args.json, "w") as f:
            json.dump({"command": [PROG] + argv, "date_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
                       "cores": os.cpu_count(), "load_start": start_load, "load_end": end_load,
                       "runs_per_mesh": args.runs, "encode_options": args.extra, "sides": sides,
                       "meshes": records}, f, indent=1)
    return 0 if all(r["sides"]["old"]["ok"] and r["sides"]["new"]["ok"] for r in records) else 1


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except Error as e:
        sys.exit(f"{PROG}: {e}")
