"""Builds of a commit for the gates that compare two builds (ci/bench-gate,
bench/gate/count_calibration.py): each in its own git worktree and build folder under
build/bench-gate/, Release, the corofem target only, with ccache where it is installed; reused by
the next call. Every failure ends the process with exit status 3, saying why on stderr.
"""
import hashlib
import os
import shutil
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
PREFIX = ["gate"]  # the calling tool's name, for its messages


def say(text):
    print(f"{PREFIX[0]}: {text}", file=sys.stderr, flush=True)


def fail(text):
    say(text)
    sys.exit(3)


def git(*args, cwd=ROOT):
    done = subprocess.run(["git", *args], cwd=cwd, capture_output=True, text=True)
    if done.returncode != 0:
        fail(f"git {' '.join(args)}: {done.stderr.strip()}")
    return done.stdout.strip()


def build_tree(source, build):
    """Configures and builds the corofem target of `source` into `build` (Release, no gates)."""
    log = os.path.join(build, "build.log")
    os.makedirs(build, exist_ok=True)
    with open(log, "w") as out:
        configure = ["cmake", "-S", source, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                     "-DCOROFEM_BUILD_TESTS=OFF", "-DCOROFEM_BUILD_BENCH=OFF"]
        if shutil.which("ccache"):  # a second worktree of nearly the same code builds in seconds
            configure.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
        for command in (configure,
                        ["cmake", "--build", build, "-j", str(os.cpu_count() or 1),
                         "--target", "corofem"]):
            # Paths relative to the worktree, so that ccache finds another worktree's objects.
            env = dict(os.environ, CCACHE_BASEDIR=source)
            if subprocess.run(command, stdout=out, stderr=subprocess.STDOUT, env=env).returncode:
                fail(f"building {source} failed: see {log}")
    binary = os.path.join(build, "bin", "corofem")
    if not os.access(binary, os.X_OK):
        fail(f"no {binary} after the build (see {log})")
    return binary


def build_ref(ref, side, twice, patch):
    """The corofem binary of `ref`, built in its own worktree (once; reused after)."""
    sha = git("rev-parse", "--verify", f"{ref}^{{commit}}")
    key = sha[:12]
    if twice:
        key += f"-{side}"  # the same commit built a second time, for the A/A check
    if patch:
        with open(patch, "rb") as f:
            key += "-patch-" + hashlib.sha256(f.read()).hexdigest()[:10]
    home = os.path.join(ROOT, "build", "bench-gate", key)
    source = os.path.join(home, "src")
    if not os.path.isdir(source):
        say(f"{side}: a worktree of {ref} ({sha[:9]}) in {source}")
        git("worktree", "add", "--detach", source, sha)
        if patch:
            git("apply", os.path.abspath(patch), cwd=source)
    say(f"{side}: building {ref} ({sha[:9]}{', patched' if patch else ''})")
    return build_tree(source, os.path.join(home, "build")), sha


def build_work_tree():
    say("NEW: building the work tree (build/release)")
    subprocess.run([os.path.join(ROOT, "ci", "build"), "release", "corofem"], check=False,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    binary = os.path.join(ROOT, "build", "release", "bin", "corofem")
    if not os.access(binary, os.X_OK):
        fail("building the work tree failed (run ci/build release corofem to see why)")
    return binary


