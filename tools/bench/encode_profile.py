#!/usr/bin/python3
"""Where `srcodec encode` spends its time and memory, stage by stage.

For each mesh: `srcodec encode MESH -o OUT.srm` with the default options (or,
with --remesh, `srcodec remesh MESH -o OUT.ply`), under `/usr/bin/time -v` for
the wall time and the peak resident memory. The stages' seconds come from the
encoder's progress lines on stderr and its --json report; each stderr line is
also stamped as it arrives, so the time between lines that no timer covers
(reading, cleaning, the component split, the measuring of the file kept,
writing) is found by difference. The resident memory of the process is
sampled every 0.1 s and the peak between two lines is charged to the stage
that the later line ends.

Prints a Markdown table (stage x mesh: seconds and share of the wall time) and
writes everything to a JSON file.

usage: /usr/bin/python3 tools/bench/encode_profile.py [--srcodec BIN] [--remesh] [--args "OPTIONS"]
                                                      [--limit SECONDS] [--json OUT.json] MESH [MESH ...]
       /usr/bin/python3 tools/bench/encode_profile.py --from-json A.json [B.json ...]   (tables of saved runs)
  SRCODEC in the environment also names the binary (default: build/tools/srcodec of this checkout).
  e.g. tools/bench/encode_profile.py --srcodec ../main/build/tools/srcodec --json /tmp/p.json \\
           ../shared/data/meshes/stanford-bunny.obj ../shared/data/meshes/igea.ply
       tools/bench/encode_profile.py --remesh --args "--levels 2 --oversample 0 --base-vertices 4000" BIG.ply
"""
import argparse
import json
import os
import re
import selectors
import shlex
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DEFAULT_SRCODEC = os.environ.get("SRCODEC", os.path.join(ROOT, "build", "tools", "srcodec"))
RSS_PERIOD = 0.1  # seconds between samples of the resident memory

NUM = r"([-+0-9.eE]+)"
# The remesher's progress lines (tools/srcodec/remesh_progress.cpp) that end a stage, with their figures.
PATTERNS = [
    ("components", re.compile(r"^remesh: components: (\d+) .*, " + NUM + " s$")),
    ("oversample", re.compile(r"^remesh: oversampled .*?: (\d+) vertices, " + NUM + " s$")),
    ("sites", re.compile(r"^remesh: sites: (\d+) .*, " + NUM + " s$")),
    ("base", re.compile(r"^remesh: base mesh: (\d+) vertices .*?, (\d+) triangles, " + NUM + " s$")),
    ("refine_set_up", re.compile(r"^remesh: refinement set up: (\d+) points .*, " + NUM + " s$")),
    ("level", re.compile(r"^remesh: level (\d+): (\d+) vertices, (\d+) triangles, (\d+) Lloyd steps.*, " + NUM +
                         " s$")),
    ("splits_undone", re.compile(r"^remesh: (?:threshold|tolerance|threshold and tolerance): .*, " + NUM + " s$")),
    ("fit", re.compile(r"^remesh: fit: .*, " + NUM + " s$")),
    ("coarsen", re.compile(r"^remesh: measured coarsening: .*, " + NUM + " s$")),
    ("untangle", re.compile(r"^remesh: untangle( \(wide search\))?: .*, " + NUM + " s$")),
    ("slivers", re.compile(r"^remesh: slivers: .*, " + NUM + " s$")),
    ("code", re.compile(r"^encode: (?:no rate option given|searching for)")),
    ("cuts", re.compile(r"^encode: (?:(\d+) cuts? estimated, (\d+) measured|(\d+) cuts? measured)")),
]


def child_pid(pid):
    """The pid of the program /usr/bin/time runs (its only child), or None before it starts."""
    try:
        with open(f"/proc/{pid}/task/{pid}/children") as f:
            kids = f.read().split()
        return int(kids[0]) if kids else None
    except (OSError, ValueError):
        return None


def rss_mb(pid):
    """Resident memory of `pid` in MB, or None once it has ended."""
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) / 1024.0
    except OSError:
        pass
    return None


def cpu_seconds(pid):
    """User + system seconds `pid` has run so far (all its threads), or None once it has ended."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            fields = f.read().rsplit(")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    except (OSError, IndexError, ValueError):
        return None


class Stopped(RuntimeError):
    """A run stopped at the time limit; `lines` are the stamped lines it printed."""

    def __init__(self, message, lines, end, cpu, peak):
        super().__init__(message)
        self.lines, self.end, self.cpu, self.peak = lines, end, cpu, peak


def run_stamped(cmd, time_file, limit=None):
    """Runs `cmd` under /usr/bin/time -v; returns (stdout, [(seconds, stderr line, peak MB since the last
    line, CPU seconds so far)], seconds to the end, peak MB after the last line). Stamps are seconds since
    the start. Past `limit` seconds the program is stopped (SIGTERM) and Stopped raised."""
    start = time.monotonic()
    p = subprocess.Popen(["/usr/bin/time", "-v", "-o", time_file] + cmd, stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE)
    sel = selectors.DefaultSelector()
    sel.register(p.stdout, selectors.EVENT_READ, "out")
    sel.register(p.stderr, selectors.EVENT_READ, "err")
    out, pending, lines = b"", b"", []
    peak, target, next_sample = 0.0, None, 0.0
    open_streams, stopped, last_cpu = 2, False, 0.0
    while open_streams:
        now = time.monotonic()
        if limit and not stopped and target and now - start > limit:
            last_cpu = cpu_seconds(target) or last_cpu
            os.kill(target, 15)
            stopped = True
        if now >= next_sample:
            target = target or child_pid(p.pid)
            mb = rss_mb(target) if target else None
            peak = max(peak, mb or 0.0)
            next_sample = now + RSS_PERIOD
        for key, _ in sel.select(timeout=RSS_PERIOD):
            data = os.read(key.fileobj.fileno(), 65536)
            if not data:
                sel.unregister(key.fileobj)
                open_streams -= 1
                continue
            if key.data == "out":
                out += data
                continue
            pending += data
            stamp = time.monotonic() - start
            cpu = (cpu_seconds(target) if target else None) or 0.0
            while b"\n" in pending:
                line, pending = pending.split(b"\n", 1)
                lines.append((stamp, line.decode(errors="replace"), peak, cpu))
                peak = 0.0
    p.wait()
    end = time.monotonic() - start
    if stopped:
        raise Stopped(f"stopped after {limit} s", lines, end, last_cpu, peak)
    if p.returncode != 0:
        last = lines[-1][1] if lines else f"exit {p.returncode}"
        raise RuntimeError(f"{' '.join(cmd)}: {last}")
    return out.decode(), lines, end, peak


def parse_time_v(path):
    """Wall seconds and peak resident MB from /usr/bin/time -v's report."""
    text = open(path).read()
    rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", text).group(1)) / 1024.0
    wall = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): ([\d:.]+)", text).group(1)
    secs = sum(float(x) * 60 ** i for i, x in enumerate(reversed(wall.split(":"))))
    user = float(re.search(r"User time \(seconds\): ([\d.]+)", text).group(1))
    system = float(re.search(r"System time \(seconds\): ([\d.]+)", text).group(1))
    return secs, rss, user + system


def stages_of(lines, end, end_cpu, tail_peak, report, remesh_only):
    """The stages in order: {stage, seconds, cpu_seconds, note, peak_mb}, from the stamped lines, the JSON
    report and the end of the run. Seconds the encoder does not time come from the stamps. A stage's CPU
    seconds are its seconds times the CPU per wall second of the window between the lines around it: on a
    loaded machine the wall seconds grow with the other jobs, the CPU seconds much less."""
    stages = []
    first_remesh, remesh_sum = None, 0.0
    code = cuts = None  # (stamp, cpu, peak) at the coding's line and at the line after the measuring
    cut_count = None
    peak, prev_stamp, prev_cpu = 0.0, 0.0, 0.0  # peak MB since the last stage's line; where its window began
    remesh_cpu = [None, None]  # CPU and stamp where the remesh began and ended

    def add(name, seconds, note, mb, ratio):
        stages.append({"stage": name, "seconds": seconds, "cpu_seconds": seconds * ratio, "note": note,
                       "peak_mb": mb})

    for stamp, line, mb, cpu in lines:
        peak = max(peak, mb)
        for kind, rx in PATTERNS:
            m = rx.match(line)
            if not m:
                continue
            g = m.groups()
            ratio = (cpu - prev_cpu) / (stamp - prev_stamp) if stamp > prev_stamp else 1.0
            if kind not in ("code", "cuts") and first_remesh is None:
                # The first remesh line's own seconds started after the read, the cleaning and the split.
                own = float(g[1]) if kind == "oversample" else float(g[-1])
                first_remesh = stamp - own
                add("read, clean" if kind == "components" else "read, clean, split components", first_remesh,
                    "stamps", 0.0, ratio)
                remesh_cpu[0] = (first_remesh * ratio, first_remesh)
            if kind == "components":
                add("split into components", float(g[1]), f"{int(g[0])} components", peak, ratio)
                remesh_sum += float(g[1])
            elif kind == "oversample":
                add("oversample", float(g[1]), f"{int(g[0])} vertices", peak, ratio)
                remesh_sum += float(g[1])
            elif kind == "sites":
                add("LBG sites", float(g[1]), f"{int(g[0])} sites", peak, ratio)
                remesh_sum += float(g[1])
            elif kind == "base":
                add("base mesh (collapses)", float(g[2]), f"{int(g[0])} base vertices, {int(g[1])} triangles", peak,
                    ratio)
                remesh_sum += float(g[2])
            elif kind == "refine_set_up":
                add("refinement set-up", float(g[1]), f"{int(g[0])} points", peak, ratio)
                remesh_sum += float(g[1])
            elif kind == "level":
                add(f"level {g[0]} (Lloyd)", float(g[4]), f"{int(g[1])} vertices, {g[3]} Lloyd steps", peak, ratio)
                remesh_sum += float(g[4])
            elif kind == "untangle":
                add("untangle" + (" (wide)" if g[0] else ""), float(g[1]), "", peak, ratio)
                remesh_sum += float(g[1])
            elif kind in ("splits_undone", "fit", "coarsen", "slivers"):
                add(kind, float(g[0]), "", peak, ratio)
                remesh_sum += float(g[0])
            elif kind == "code":
                code = (stamp, cpu, peak, ratio)
            elif kind == "cuts":
                cuts = (stamp, cpu, peak, ratio)
                cut_count = f"{g[0]} cuts estimated, {g[1]} measured" if g[0] else f"{g[2]} cuts"
            if kind not in ("code", "cuts"):
                remesh_cpu[1] = (cpu, stamp)
            peak, prev_stamp, prev_cpu = 0.0, stamp, cpu
            break
    if report is None:  # stopped at the time limit: what ran after the last stage's line
        ratio = (end_cpu - prev_cpu) / (end - prev_stamp) if end > prev_stamp else 1.0
        add("(stopped: the stage after the last line)", end - prev_stamp, "stamps", peak, ratio)
        return stages, {"stopped": True}
    remesh_seconds = report["remesh_seconds"] if not remesh_only else report["seconds"]
    if first_remesh is None:  # no remesh line (an input that is its own base mesh)
        first_remesh = max(0.0, (code[0] if code else end) - remesh_seconds - report.get("coding_seconds", 0.0))
        add("read, clean, split components", first_remesh, "stamps", 0.0, 1.0)
    span = remesh_cpu[0] and remesh_cpu[1] and remesh_cpu[1][1] - remesh_cpu[0][1]
    remesh_ratio = (remesh_cpu[1][0] - remesh_cpu[0][0]) / span if span else 1.0
    if remesh_only:
        # `srcodec remesh` reports no line at the remesh's end: the untimed rest is the time between the first
        # and the last remesh line that no stage covers; after the last line come the tangled places, the
        # levels' error figures and the writing.
        last = remesh_cpu[1][1] if remesh_cpu[1] else first_remesh
        add("remesh: untimed rest", last - first_remesh - remesh_sum, "", 0.0, remesh_ratio)
        tail_ratio = (end_cpu - remesh_cpu[1][0]) / (end - last) if remesh_cpu[1] and end > last else 1.0
        add("measure levels, write", end - last, "stamps", tail_peak, tail_ratio)
        return stages, {"remesh": remesh_seconds}
    if code:
        # The remesh began coding + remesh seconds before the coding's line: what came before is the read and
        # the cleaning; the component split belongs to the remesh's untimed rest.
        read = stages[0]
        read["stage"] = "read, clean"
        ratio = read["cpu_seconds"] / read["seconds"] if read["seconds"] > 0 else 1.0
        read["seconds"] = code[0] - report["coding_seconds"] - remesh_seconds
        read["cpu_seconds"] = read["seconds"] * ratio
    # The remesh's total minus its stages: the component split, the joins, the levels' bookkeeping.
    add("remesh: untimed rest", remesh_seconds - remesh_sum, "", 0.0, remesh_ratio)
    # The memory sampled up to the coding's line (the remesh's tail, the coding) and up to the line after the
    # measuring (rate control, measuring) is charged to the coding and to the rate control.
    add("coding", report["coding_seconds"], "", code[2] if code else 0.0, code[3] if code else 1.0)
    rate_ratio = cuts[3] if cuts else 1.0
    add("rate control (cuts decoded, measured)", report["rate_seconds"], cut_count if cuts else "",
        cuts[2] if cuts else 0.0, rate_ratio)
    if code and cuts:
        add("measure the file kept", cuts[0] - code[0] - report["rate_seconds"], "stamps", 0.0, rate_ratio)
        tail_ratio = (end_cpu - cuts[1]) / (end - cuts[0]) if end > cuts[0] else 1.0
        add("write, exit", end - cuts[0], "stamps", tail_peak, tail_ratio)
    else:  # another rate option: no line after the measuring
        add("measure, write, exit", end - first_remesh - remesh_seconds - report["coding_seconds"] -
            report["rate_seconds"], "stamps", tail_peak, 1.0)
    return stages, {"remesh": remesh_seconds, "coding": report["coding_seconds"], "rate": report["rate_seconds"],
                    "cuts": cut_count}


def profile(srcodec, mesh, remesh_only, extra, tmp, limit=None):
    """One run: its stages, wall time, peak memory and the encoder's own figures; a run stopped at `limit`
    seconds has the stages it ended."""
    out = os.path.join(tmp, "out.ply" if remesh_only else "out.srm")
    cmd = [srcodec, "remesh" if remesh_only else "encode", mesh, "-o", out, "--json"] + extra
    time_file = os.path.join(tmp, "time.txt")
    load_before = os.getloadavg()
    try:
        stdout, lines, end, tail_peak = run_stamped(cmd, time_file, limit)
        report = json.loads(stdout.strip().splitlines()[-1])
    except Stopped as e:
        lines, end, tail_peak, report = e.lines, e.end, e.peak, None
    load_after = os.getloadavg()
    wall, rss, cpu = parse_time_v(time_file)
    stages, totals = stages_of(lines, end, cpu, tail_peak, report, remesh_only)
    return {"mesh": mesh, "command": cmd, "wall_seconds": wall, "stamped_seconds": end, "cpu_seconds": cpu,
            "peak_rss_mb": rss, "load_before": load_before, "load_after": load_after, "totals": totals,
            "input_vertices": (report or {}).get("input_vertices"), "stages": stages,
            "lines": [{"seconds": t, "line": l, "peak_mb": mb, "cpu_seconds": c} for t, l, mb, c in lines],
            "report": report, "stopped_after": limit if report is None else None}


def table(runs):
    """Markdown: one row per stage, one column per mesh: the wall seconds and their share of the wall time,
    then the CPU seconds (estimated per window, stages_of) and their share of the CPU time."""
    order = stage_order(runs)
    rows = ["| stage | " + " | ".join(os.path.basename(r["mesh"]) for r in runs) + " |",
            "|---|" + "---:|" * len(runs)]
    for stage in order:
        cells = []
        for r in runs:
            hits = [s for s in r["stages"] if s["stage"] == stage]
            secs, cpu = sum(s["seconds"] for s in hits), sum(s["cpu_seconds"] for s in hits)
            cells.append(f"{secs:.2f} s {100 * secs / r['wall_seconds']:.1f}% (CPU {cpu:.2f} s "
                         f"{100 * cpu / r['cpu_seconds']:.1f}%)" if hits else "")
        rows.append(f"| {stage} | " + " | ".join(cells) + " |")
    rows.append("| **total** (time -v: wall; CPU = user + sys) | " +
                " | ".join(f"**{r['wall_seconds']:.2f} s** (CPU {r['cpu_seconds']:.2f} s)" for r in runs) + " |")
    rows.append("| stages summed (wall) | " + " | ".join(f"{sum_wall(r):.2f} s" for r in runs) + " |")
    rows.append("| peak RSS | " + " | ".join(f"{r['peak_rss_mb']:.0f} MB" for r in runs) + " |")
    rows.append("| load average (1 min) before, after | " +
                " | ".join(f"{r['load_before'][0]:.2f}, {r['load_after'][0]:.2f}" for r in runs) + " |")
    return "\n".join(rows)


def figures_table(runs):
    """Markdown: what each stage worked on (vertices, Lloyd steps, cuts), where the encoder says."""
    order = [name for name in stage_order(runs)
             if any(st["stage"] == name and st["note"] not in ("", "stamps") for r in runs for st in r["stages"])]
    rows = ["| stage | " + " | ".join(os.path.basename(r["mesh"]) for r in runs) + " |", "|---|" + "---|" * len(runs)]
    for stage in order:
        cells = []
        for r in runs:
            notes = [st["note"] for st in r["stages"] if st["stage"] == stage and st["note"] != "stamps"]
            cells.append("; ".join(notes))
        rows.append(f"| {stage} | " + " | ".join(cells) + " |")
    return "\n".join(rows)


def stage_order(runs):
    """Every run's stages in one order: a stage one run has and the others lack goes after the stage before
    it in that run."""
    order = []
    for r in runs:
        prev = None
        for st in r["stages"]:
            name = st["stage"]
            if name not in order:
                order.insert(order.index(prev) + 1 if prev in order else len(order), name)
            prev = name
    return order


def sum_wall(run):
    """The stages' wall seconds summed: close to the wall time when no time went unseen."""
    return sum(s["seconds"] for s in run["stages"])


def memory_table(runs):
    """Markdown: the peak resident memory sampled while each stage ran (0: not sampled, a stage under 0.1 s)."""
    rows = ["| stage | " + " | ".join(os.path.basename(r["mesh"]) for r in runs) + " |", "|---|" + "---|" * len(runs)]
    order = [name for name in stage_order(runs)
             if any(st["stage"] == name and st["peak_mb"] > 0 for r in runs for st in r["stages"])]
    for stage in order:
        cells = []
        for r in runs:
            mbs = [s["peak_mb"] for s in r["stages"] if s["stage"] == stage]
            cells.append(f"{max(mbs):.0f}" if mbs and max(mbs) > 0 else "")
        rows.append(f"| {stage} | " + " | ".join(cells) + " |")
    return "\n".join(rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("meshes", nargs="*")
    ap.add_argument("--srcodec", default=DEFAULT_SRCODEC)
    ap.add_argument("--remesh", action="store_true", help="profile `srcodec remesh` instead of `srcodec encode`")
    ap.add_argument("--args", default="", help="more options for the srcodec command")
    ap.add_argument("--json", help="write every figure here")
    ap.add_argument("--limit", type=float, help="stop a run after this many seconds (its stages so far are kept)")
    ap.add_argument("--from-json", nargs="+", default=[], metavar="JSON",
                    help="print the tables of runs saved with --json (before those of MESH ...)")
    a = ap.parse_args()
    runs = []
    for path in a.from_json:
        with open(path) as f:
            runs += json.load(f)
    with tempfile.TemporaryDirectory() as tmp:
        for mesh in a.meshes:
            print(f"running {os.path.basename(mesh)} ...", file=sys.stderr, flush=True)
            runs.append(profile(a.srcodec, mesh, a.remesh, shlex.split(a.args), tmp, a.limit))
    if not runs:
        ap.error("give meshes or --from-json")
    print(table(runs))
    print()
    print("What the stages worked on:")
    print()
    print(figures_table(runs))
    print()
    print("Peak resident MB sampled while each stage ran:")
    print()
    print(memory_table(runs))
    if a.json and a.meshes:
        with open(a.json, "w") as f:
            json.dump(runs, f, indent=1)


if __name__ == "__main__":
    main()
