"""Other revisions of slc beside this checkout, for the tools that compare builds
(`tools/same-images`, `tools/ab-bench`): git worktrees of a revision, `slc` built in each
into its own target folder.
"""
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# The tool that runs (its name prefixes the errors).
TOOL = os.path.basename(sys.argv[0]) if sys.argv and sys.argv[0] else "tools"


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def git(*args, cwd=ROOT, check=True):
    """git's output, stripped."""
    return subprocess.run(
        ["git", *args], cwd=cwd, check=check, stdout=subprocess.PIPE, text=True
    ).stdout.strip()


def commit_of(rev):
    """The commit `rev` names."""
    return git("rev-parse", "--verify", rev + "^{commit}")


def worktree(path, rev, shared_parent):
    """A detached worktree of `rev` at `path` (made if missing); checks an existing one."""
    want = commit_of(rev)
    if os.path.isdir(path):
        have = git("rev-parse", "HEAD", cwd=path)
        if have != want:
            raise SystemExit(
                "%s: %s is at %s, not %s (%s): remove it or give another folder"
                % (TOOL, path, have[:10], rev, want[:10])
            )
    else:
        log("git worktree add %s %s" % (path, rev))
        git("worktree", "add", "--detach", path, want)
    # The scenes read ../shared beside the checkout: link it where this script made the folder.
    shared = os.path.join(os.path.dirname(os.path.abspath(path)), "shared")
    ours = os.path.realpath(os.path.join(ROOT, "..", "shared"))
    if shared_parent and not os.path.exists(shared) and os.path.isdir(ours):
        os.symlink(ours, shared)
    return want


def build(checkout, jobs):
    """`slc` of `checkout`, built in release into the checkout's own target folder."""
    cmd = ["cargo", "build", "--release", "-p", "slc-app", "--bin", "slc"]
    cmd += ["--target-dir", os.path.join(checkout, "target")]
    if jobs:
        cmd += ["-j", str(jobs)]
    log("%s: %s" % (checkout, " ".join(cmd)))
    t = time.time()
    subprocess.run(cmd, cwd=checkout, check=True)
    log("built in %.0f s" % (time.time() - t))


def slc_of(checkout):
    """The `slc` built in `checkout`."""
    path = os.path.join(checkout, "target", "release", "slc")
    if not os.access(path, os.X_OK):
        raise SystemExit("%s: no slc at %s (build it, or drop --no-build)" % (TOOL, path))
    return path
