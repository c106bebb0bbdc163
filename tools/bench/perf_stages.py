#!/usr/bin/python3
"""The hot functions of each encoder stage, from a `perf record -g` profile.

Reads `perf script` output (call chains, leaf first) on stdin. Each sample is
charged to the innermost stage function on its stack (the table below: the
entry point of each step of encode_mesh and of the remesher), then to its leaf
function (self time) and to every function on its stack below the stage
(inclusive time). Prints, per stage, its share of all samples and its top
functions with their share of the stage.

usage: perf record -e cpu-clock -F 250 --call-graph dwarf -o P.data -- srcodec encode MESH -o OUT.srm
       perf script -i P.data --no-inline -F comm,tid,time,event,ip,sym \
           | /usr/bin/python3 tools/bench/perf_stages.py [TOP]
"""
import bisect
import re
import sys
from collections import Counter, defaultdict

# (stage, pattern on a frame's function name): the first stage in this order with a frame on the stack is the
# sample's (rate control measures cuts with the same StreamCutter::psnr as the measuring of the file kept, so
# it comes first; the remesher's own steps before the remesh as a whole).
STAGES = [
    ("rate control", re.compile(r"^srcodec::(knee_of_stream|segment_bytes_for_psnr|whole_stream_psnr)$")),
    ("LBG sites", re.compile(r"^srcodec::lbg_sites$")),
    ("boundary tips", re.compile(r"^srcodec::add_boundary_tip_sites$")),
    ("base mesh (collapses)", re.compile(r"^srcodec::build_base_mesh$")),
    ("oversample", re.compile(r"^srcodec::oversample$")),
    ("fit", re.compile(r"^srcodec::fit_to_surface$")),
    ("untangle", re.compile(r"^srcodec::untangle$|^srcodec::UntangleInput::UntangleInput$")),
    ("slivers", re.compile(r"^srcodec::relax_slivers$")),
    ("levels (refine, Lloyd)", re.compile(r"^srcodec::refine$")),
    ("components", re.compile(r"^srcodec::split_into_manifold_components$")),
    ("coding", re.compile(r"^srcodec::encode_srm$")),
    ("measure the file kept", re.compile(r"^srcodec::StreamCutter::psnr$")),
    ("read, clean", re.compile(r"^srcodec::read_triangle_mesh$")),
    ("write", re.compile(r"^srcodec::write_file_atomically$")),
    ("remesh (other)", re.compile(r"^srcodec::remesh$")),
]
HEADER = re.compile(r"^\S+\s+(\d+)\s+([\d.]+):")  # perf script -F comm,tid,time,...: a sample's first line
FRAME = re.compile(r"^\s+[0-9a-f]+\s+(.*?)\s*$")  # perf script -F ...,ip,sym: an address and a symbol


def short(sym):
    """A demangled symbol without its argument list and return type, to keep the table narrow."""
    sym = re.sub(r"\+0x[0-9a-f]+$", "", sym).replace("(anonymous namespace)::", "")
    depth, out = 0, []
    for ch in sym:  # drop template and argument lists
        if ch in "<(":
            depth += 1
        elif ch in ">)":
            depth -= 1
        elif depth == 0:
            out.append(ch)
    name = "".join(out).strip().replace(" const::", "::")  # a lambda in a const member function
    return name.split(" ")[-1] if " " in name else name


# Frames of the thread pool and of the kernel's thread start, on every worker's stack: no work of their own.
PLUMBING = re.compile(r"^(\[unknown\]|clone3?|start_thread|tbb::|std::_Function_handler|std::thread)")


def samples(stream):
    """Each sample's thread, time and frames (function names, leaf first)."""
    tid, when, frames = None, 0.0, []
    for line in stream:
        h = HEADER.match(line)
        if h:
            if frames:
                yield tid, when, frames
            tid, when, frames = int(h.group(1)), float(h.group(2)), []
            continue
        m = FRAME.match(line)
        if m:
            frames.append(short(m.group(1)))
    if frames:
        yield tid, when, frames


def stage_of(frames):
    """The sample's stage (STAGES) and how many frames lie below its stage function, or (None, all)."""
    for stage, rx in STAGES:
        for i, f in enumerate(frames):
            if rx.search(f):
                return stage, i
    return None, len(frames)


def main():
    top = int(sys.argv[1]) if len(sys.argv) > 1 else 8
    every = list(samples(sys.stdin))
    main_tid = min(t for t, _, _ in every)  # the process's first thread has the smallest id
    # A worker thread's stack ends in the thread pool, not in the stage that handed it the work: it is
    # charged to the stage of the main thread's sample nearest in time (the main thread waits in, or
    # works on, the same parallel loop).
    main_times, main_stages = [], []
    for tid, when, frames in every:
        if tid == main_tid:
            main_times.append(when)
            main_stages.append(stage_of(frames)[0])
    per_stage = Counter()
    leaf = defaultdict(Counter)
    inclusive = defaultdict(Counter)
    for tid, when, frames in every:
        stage, depth = stage_of(frames)
        if tid != main_tid and stage is None and main_times:
            i = bisect.bisect_left(main_times, when)
            near = min((j for j in (i - 1, i) if 0 <= j < len(main_times)), key=lambda j: abs(main_times[j] - when))
            stage = main_stages[near]
        stage = stage or "(outside the stages)"
        per_stage[stage] += 1
        leaf[stage][frames[0]] += 1
        for name in set(frames[:depth]):
            if not PLUMBING.match(name):
                inclusive[stage][name] += 1
    total = len(every)
    print(f"{total} samples, {sum(1 for t, _, _ in every if t != main_tid)} of them on worker threads")
    for stage, n in per_stage.most_common():
        print(f"\n## {stage}: {n} samples, {100 * n / total:.1f}% of all\n")
        print("| self | function | | inclusive | function |")
        print("|---:|---|---|---:|---|")
        a, b = leaf[stage].most_common(top), inclusive[stage].most_common(top)
        for i in range(max(len(a), len(b))):
            left = f"{100 * a[i][1] / n:.1f}% | `{a[i][0]}`" if i < len(a) else " | "
            right = f"{100 * b[i][1] / n:.1f}% | `{b[i][0]}`" if i < len(b) else " | "
            print(f"| {left} | | {right} |")


if __name__ == "__main__":
    main()
