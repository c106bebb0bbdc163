"""Running the srcodec binary from the benchmark scripts in this folder (adaptive_target.py,
corpus_remesh.py, decoded_folds.py, default_rate.py, remesh_quality.py): where the binary and the corpus
are, one call that runs a command and says what failed, and the measurements they share.

SRCODEC in the environment names another binary (default: build/tools/srcodec of this checkout);
REMESH_EXPERIMENT another remesh_experiment (default: build/tools/remesh_experiment), the program with
the switches for experiments (--tolerance, --no-fit-surface, --no-untangle, --no-relax-slivers,
--unsplit-tangles) that the user's `srcodec remesh` does not have."""
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SRCODEC = os.environ.get("SRCODEC", os.path.join(ROOT, "build", "tools", "srcodec"))
REMESH_EXPERIMENT = os.environ.get("REMESH_EXPERIMENT", os.path.join(ROOT, "build", "tools", "remesh_experiment"))
CORPUS = os.path.join(ROOT, "..", "shared", "data", "meshes")
MESH_SUFFIXES = (".obj", ".ply", ".off", ".stl")  # what srcodec reads


class Failed(RuntimeError):
    """A srcodec command that exited non-zero; its text is the command and the last line srcodec printed."""


def failure(args, returncode, stderr):
    """The Failed of `srcodec ARGS` that exited with `returncode`, having printed `stderr`."""
    last = (stderr.strip().splitlines() or [f"exit {returncode}"])[-1]
    return Failed(f"srcodec {' '.join(args)}: {last}")


def run(args, binary=SRCODEC):
    """Runs `srcodec ARGS` (or `binary`, e.g. REMESH_EXPERIMENT); returns what it printed on stdout. Raises
    Failed when it exits non-zero."""
    p = subprocess.run([binary] + args, capture_output=True, text=True)
    if p.returncode != 0:
        raise failure(args, p.returncode, p.stderr)
    return p.stdout


def run_json(args, binary=SRCODEC):
    """run() of a command given --json: its output read as JSON."""
    return json.loads(run(args, binary))


def corpus_meshes():
    """The names of the corpus's meshes, sorted."""
    return sorted(f for f in os.listdir(CORPUS) if f.endswith(MESH_SUFFIXES))


def psnr(reference, test, extra=()):
    """`srcodec compare REFERENCE TEST` (with `extra` options)'s PSNR in dB."""
    return run_json(["compare", reference, test, "--json"] + list(extra))["psnr"]


def draco_point(mesh, qp, decoded):
    """Draco's round trip of `mesh` at `qp` quantization bits (`-cl 10`), its decoded mesh written to
    `decoded`: (bytes, PSNR of the decoded mesh against `mesh`)."""
    size = run_json(["draco", mesh, "--qp", str(qp), "--decoded", decoded, "--json"])["bytes"]
    return size, psnr(mesh, decoded)


def or_exit(call, *args):
    """call(*args), or the script's exit with Failed's text (and status 1) when a command failed."""
    try:
        return call(*args)
    except Failed as e:
        sys.exit(f"{os.path.basename(sys.argv[0])}: {e}")
