#!/usr/bin/env python3
"""A real Slurm job array (docs/batch-runs.md#slurm-a-job-array): tools/slurm.sh starts a
single-node cluster on localhost (munged, slurmctld, slurmd) in a scratch folder; the documented
job scripts tools/fuzz-array.sbatch and tools/bench-array.sbatch are submitted with
`sbatch --array=1-3`, and `shadowcert merge` of the three shards must equal one unsharded run of
the same command in every figure but the times.

    slurm_array_test.py SHADOWCERT_BINARY SOURCE_DIR

Each array loses one task on the way: shard 2 is cancelled with scancel while it runs (fuzz:
once it is running; bench: once its bench.json holds a finished scene but says
"complete": false). The merge must then refuse (fuzz: shard 2/3 missing; bench: shard 2
interrupted), and refuse a shard given twice; shard 2 is submitted again alone
(`sbatch --array=2 ... 3`) and the merge of the three is the single run: nothing lost, nothing
counted twice.

Without accounting there is no sacct: a job's end is read from squeue (it leaves the queue) and
its state and exit code from `scontrol show job` (kept for MinJobAge).

Exit 0 pass, 1 fail, 77 skip (ctest's SKIP_RETURN_CODE): Slurm or munge not installed, not
root, or the cluster did not start, outside CI; SHADOWCERT_REQUIRE_SLURM=1 (set by
`tools/dev.sh test`) fails instead. No EGL device skips as the GL tests do
(SHADOWCERT_REQUIRE_GL=1 fails). SHADOWCERT_KEEP_SLURM_RUN=1 keeps the scratch folder.
"""
import json
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time

SKIP = 77
SHARDS = 3
CANCELLED = 2  # the shard cancelled mid-run and submitted again
# sbatch's command line overrides the scripts' #SBATCH lines (4 CPUs and 8 GB per task, sized
# for a real campaign): one CPU each, so two tasks run at once on a 2-core machine.
TASK_RESOURCES = ["--cpus-per-task=1", "--mem=1G", "--time=00:20:00"]
# A campaign with findings (kim-float fails on some cases: reproducers shrunk, the first two by
# case index kept) and GL cases; about 10 s of work in all on a 2-core llvmpipe machine.
# 1200 cases (400 a shard, several seconds): at 300 a shard could end before the cancel of a
# running shard landed (a race seen on an idle machine, 2026-12-06).
FUZZ = ["--gl", "--seed", "1", "--cases", "1200", "--triangles", "30", "--methods", "exact,kim-float,refedge-float",
        "--shrink-findings", "--max-reproducers", "2", "--gl-methods", "cs,pertri", "--gl-size", "32x24"]
# The hard suite (21 scenes, 7 per shard) small: about 0.5 s a scene.
BENCH = ["--suite", "hard", "--size", "64x48", "--frames", "1", "--methods", "cpu,cs/exact,pertri,shadowmap/512",
         "--no-plots"]
WAIT_SECONDS = 600

# Keys that are not figures of the run (tests/cli/shard_merge_test.cpp's figures() and
# bench_command_test.cpp's kNotFigures): times and rates, the thread count, the moment, the
# tree's state, the command line, the merge's list of its shards, where reproducers went.
NOT_FIGURES = {"seconds", "cases_per_second", "shrink_seconds", "exact_seconds", "exact_image_seconds", "edge_truth_seconds", "time",
               "date", "git_commit", "git_dirty", "command", "threads", "shards"}


class Failure(Exception):
    pass


def flag(name):
    return os.environ.get(name, "") not in ("", "0")


def skip_or_fail(required, message):
    if required:
        print("FAIL: " + message)
        return 1
    print("SKIP: " + message)
    return SKIP


def differences(a, b, path="", reproducer=False):
    """The key paths where a and b differ, but for NOT_FIGURES (and a reproducer's file)."""
    if isinstance(a, dict) and isinstance(b, dict):
        found = []
        for key in sorted(set(a) | set(b)):
            if key in NOT_FIGURES or (reproducer and key == "file"):
                continue
            at = path + "." + key if path else key
            if key not in a or key not in b:
                found.append(at + " is in one file only")
            else:
                found += differences(a[key], b[key], at, reproducer or key == "reproducers")
        return found
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return ["%s: %d items against %d" % (path, len(a), len(b))]
        found = []
        for i, (x, y) in enumerate(zip(a, b)):
            found += differences(x, y, "%s[%d]" % (path, i), reproducer)
        return found
    return [] if a == b else ["%s: %r against %r" % (path, a, b)]


def free_port_pair():
    """A port P with P and P + 1 free on localhost (slurmctld and slurmd)."""
    for _ in range(50):
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            port = s.getsockname()[1]
        if port >= 65535:
            continue
        try:
            with socket.socket() as s:
                s.bind(("127.0.0.1", port + 1))
            return port
        except OSError:
            continue
    raise Failure("no two free neighbouring ports on localhost")


def task_ids(text):
    """The array task ids of scontrol's ArrayTaskId: one id, or while pending a set such as
    '1-3', '2,3' or '1-3%2' (a limit on how many run at once)."""
    ids = []
    for part in text.split("%")[0].split(","):
        first, _, last = part.partition("-")
        ids += range(int(first), int(last or first) + 1)
    return ids


class Cluster:
    def __init__(self, source, work, env):
        self.source, self.work, self.env = source, work, env

    def run(self, args, check=True):
        r = subprocess.run(args, cwd=self.work, env=self.env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           text=True, timeout=120, check=False)
        if check and r.returncode != 0:
            raise Failure("%s exited %d:\n%s" % (" ".join(args), r.returncode, r.stdout))
        return r

    def submit(self, script, array, arguments):
        """sbatch --array=ARRAY tools/SCRIPT SHARDS ARGUMENTS...; the array's job id."""
        r = self.run(["sbatch", "--parsable", "--array=" + array] + TASK_RESOURCES +
                     [os.path.join(self.source, "tools", script), str(SHARDS)] + arguments)
        return r.stdout.strip().split(";")[0]

    def tasks(self, job):
        """{array task id: (state, exit code)} of an array job, from scontrol."""
        r = self.run(["scontrol", "-o", "show", "job", job])
        found = {}
        for line in r.stdout.splitlines():
            fields = dict(f.split("=", 1) for f in line.split() if "=" in f)
            if "ArrayTaskId" in fields:
                for k in task_ids(fields["ArrayTaskId"]):
                    found[k] = (fields.get("JobState"), fields.get("ExitCode"))
        return found

    def state(self, job, task):
        return self.tasks(job).get(task, (None, None))[0]

    def wait(self, job):
        """Polls squeue until the array has left the queue; its tasks' states and exit codes."""
        deadline = time.monotonic() + WAIT_SECONDS
        while self.run(["squeue", "-h", "-j", job, "-o", "%i"], check=False).stdout.strip():
            if time.monotonic() > deadline:
                raise Failure("job %s still queued after %d s:\n%s" % (
                    job, WAIT_SECONDS, self.run(["squeue"], check=False).stdout))
            time.sleep(0.5)
        return self.tasks(job)

    def wait_for(self, what, condition, timeout=WAIT_SECONDS):
        deadline = time.monotonic() + timeout
        while not condition():
            if time.monotonic() > deadline:
                raise Failure("waited %d s for %s" % (timeout, what))
            time.sleep(0.05)

    def cancel(self, job, task):
        self.run(["scancel", "%s_%d" % (job, task)])
        self.wait_for("task %s_%d to end after scancel" % (job, task),
                      lambda: self.state(job, task) not in ("RUNNING", "COMPLETING", "PENDING"), 60)
        state = self.state(job, task)
        if state != "CANCELLED":
            raise Failure("task %s_%d was %s, not CANCELLED: it finished before the cancel landed "
                          "(give it more work)" % (job, task, state))


def shadowcert(binary, args, work):
    start = time.monotonic()
    r = subprocess.run([binary] + args, cwd=work, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                       check=False)
    return r, time.monotonic() - start


def expect_tasks(tasks, expected, what):
    """Every task of `expected` ended with exit code 0 or 1 (1: a finding) and COMPLETED or FAILED."""
    for k in expected:
        state, code = tasks.get(k, (None, None))
        if state not in ("COMPLETED", "FAILED") or code not in ("0:0", "1:0"):
            raise Failure("%s task %d: %s, exit code %s (runs/%s-%d.log)" % (what, k, state, code, what, k))


def read_json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def check_merge(binary, work, name, files, single, single_exit):
    """merge FILES equals the single run in every figure; the merge's exit code is the single run's."""
    out = "runs/%s.json" % name
    merge, _ = shadowcert(binary, ["merge"] + files + ["--json", out], work)
    if merge.returncode != single_exit:
        raise Failure("merge of the %s shards exited %d, the single run %d:\n%s"
                      % (name, merge.returncode, single_exit, merge.stdout))
    merged = read_json(os.path.join(work, out))
    found = differences(merged, single)
    if found:
        raise Failure("the merged %s differs from the single run at %d keys:\n  %s"
                      % (name, len(found), "\n  ".join(found[:20])))
    return merged


def expect_refused(binary, work, files, expected, what):
    r, _ = shadowcert(binary, ["merge"] + files + ["--json", "runs/refused.json"], work)
    if r.returncode != 2 or expected not in r.stdout:
        raise Failure("merge of %s: exit %d, expected 2 saying '%s':\n%s" % (what, r.returncode, expected, r.stdout))
    return next(line for line in r.stdout.splitlines() if expected in line)


def duplicate(work, shard_file):
    """A copy of a shard's file, as a shard run twice leaves."""
    root, extension = os.path.splitext(shard_file)
    copy = root + "-again" + extension
    shutil.copyfile(os.path.join(work, shard_file), os.path.join(work, copy))
    return copy


def fuzz_seconds(run):
    """A fuzz run's own time: its exact part and its GL part."""
    return run["seconds"] + (run["gl"]["seconds"] if run["gl"] else 0.0)


def fuzz_array(cluster, binary, work, report):
    single, single_seconds = shadowcert(binary, ["fuzz"] + FUZZ + ["--threads", "1", "--json", "single/fuzz.json",
                                                                    "--out", "single/reproducers"], work)
    if single.returncode > 1:
        raise Failure("the single fuzz run exited %d:\n%s" % (single.returncode, single.stdout))
    whole = read_json(os.path.join(work, "single/fuzz.json"))
    if whole["methods"]["kim-float"]["failures"] <= 2 or len(whole["reproducers"]) != 2:
        raise Failure("the campaign found too little to check the reproducers' merge: pick another seed")

    start = time.monotonic()
    job = cluster.submit("fuzz-array.sbatch", "1-%d" % SHARDS, FUZZ)
    cluster.wait_for("fuzz shard %d to run" % CANCELLED, lambda: cluster.state(job, CANCELLED) == "RUNNING")
    cluster.cancel(job, CANCELLED)
    tasks = cluster.wait(job)
    expect_tasks(tasks, [k for k in range(1, SHARDS + 1) if k != CANCELLED], "fuzz")
    shard_files = ["runs/fuzz-%d.json" % k for k in range(1, SHARDS + 1)]
    if os.path.exists(os.path.join(work, shard_files[CANCELLED - 1])):
        raise Failure("the cancelled fuzz shard wrote its --json file")
    kept = [f for k, f in enumerate(shard_files, 1) if k != CANCELLED]
    missing = expect_refused(binary, work, kept, "missing shard %d/%d" % (CANCELLED, SHARDS), "the shards but the cancelled one")
    twice = expect_refused(binary, work, kept + [duplicate(work, kept[0])], "again", "a shard given twice")

    again = cluster.submit("fuzz-array.sbatch", str(CANCELLED), FUZZ)
    expect_tasks(cluster.wait(again), [CANCELLED], "fuzz")
    wall = time.monotonic() - start
    merged = check_merge(binary, work, "fuzz", list(reversed(shard_files)), whole, single.returncode)
    report["fuzz"] = {
        "single_seconds": round(single_seconds, 1), "single_exit": single.returncode, "array_wall_seconds": round(wall, 1),
        "shard_seconds": [round(fuzz_seconds(read_json(os.path.join(work, f))), 2) for f in shard_files],
        "merged_seconds": round(fuzz_seconds(merged), 2), "single_run_seconds": round(fuzz_seconds(whole), 2),
        "shard_cases": [read_json(os.path.join(work, f))["cases"] for f in shard_files],
        "cases": merged["cases"], "kim_float_failures": merged["methods"]["kim-float"]["failures"],
        "gl_cases": merged["gl"]["cases"], "reproducer_cases": [r["case"] for r in merged["reproducers"]],
        "refused_missing": missing, "refused_twice": twice}


def bench_array(cluster, binary, work, report):
    single, single_seconds = shadowcert(binary, ["bench"] + BENCH + ["--out", "single/bench"], work)
    if single.returncode > 1:
        raise Failure("the single bench run exited %d:\n%s" % (single.returncode, single.stdout))
    whole = read_json(os.path.join(work, "single/bench/bench.json"))

    start = time.monotonic()
    job = cluster.submit("bench-array.sbatch", "1-%d" % SHARDS, BENCH)
    partial = os.path.join(work, "runs/bench-%d/bench.json" % CANCELLED)

    def one_scene_done():
        try:
            j = read_json(partial)
        except (OSError, ValueError):
            return False
        return len(j["scenes"]) >= 1 and not j["complete"]

    cluster.wait_for("bench shard %d to finish a scene" % CANCELLED, one_scene_done)
    cluster.cancel(job, CANCELLED)
    tasks = cluster.wait(job)
    expect_tasks(tasks, [k for k in range(1, SHARDS + 1) if k != CANCELLED], "bench")
    cut = read_json(partial)
    if cut["complete"]:
        raise Failure("the cancelled bench shard says complete")
    shard_files = ["runs/bench-%d/bench.json" % k for k in range(1, SHARDS + 1)]
    interrupted = expect_refused(binary, work, shard_files, "'complete' is false", "an interrupted shard")
    kept = [f for k, f in enumerate(shard_files, 1) if k != CANCELLED]
    missing = expect_refused(binary, work, kept, "missing shard %d/%d" % (CANCELLED, SHARDS), "the shards but the cancelled one")
    twice = expect_refused(binary, work, kept + [duplicate(work, kept[0])], "again", "a shard given twice")

    again = cluster.submit("bench-array.sbatch", str(CANCELLED), BENCH)
    expect_tasks(cluster.wait(again), [CANCELLED], "bench")
    wall = time.monotonic() - start
    merged = check_merge(binary, work, "bench", list(reversed(shard_files)), whole, single.returncode)
    report["bench"] = {
        "single_seconds": round(single_seconds, 1), "single_exit": single.returncode, "array_wall_seconds": round(wall, 1),
        "shard_seconds": [round(read_json(os.path.join(work, f))["seconds"], 2) for f in shard_files],
        "merged_seconds": round(merged["seconds"], 2), "single_run_seconds": round(whole["seconds"], 2),
        "shard_scenes": [len(read_json(os.path.join(work, f))["scenes"]) for f in shard_files],
        "cancelled_after_scenes": len(cut["scenes"]), "scenes": merged["totals"]["scenes"],
        "runs": merged["totals"]["runs"], "refused_interrupted": interrupted, "refused_missing": missing,
        "refused_twice": twice}


def main(argv):
    if len(argv) != 3:
        print("usage: slurm_array_test.py SHADOWCERT_BINARY SOURCE_DIR")
        return 2
    binary, source = os.path.abspath(argv[1]), os.path.abspath(argv[2])
    required = flag("SHADOWCERT_REQUIRE_SLURM")
    missing = [p for p in ("munged", "slurmctld", "slurmd", "sbatch", "squeue", "scancel", "scontrol")
               if shutil.which(p) is None]
    if missing:
        return skip_or_fail(required, "no %s (Debian: apt-get install slurm-wlm munge; tools/dev.sh installs them)"
                            % ", ".join(missing))
    if os.geteuid() != 0:
        return skip_or_fail(required, "tools/slurm.sh runs slurmd, which must be root")

    # A unix socket's path is at most 107 bytes: the scratch folder stays short.
    work = tempfile.mkdtemp(prefix="shadowcert_slurm_", dir="/tmp")
    os.chmod(work, 0o755)  # munged's socket folder and every folder above it must be enterable by all
    slurm_dir = os.path.join(work, "slurm")
    script = os.path.join(source, "tools", "slurm.sh")
    env = dict(os.environ)
    env["PATH"] = os.path.dirname(binary) + os.pathsep + env.get("PATH", "")
    env["SLURM_CONF"] = os.path.join(slurm_dir, "slurm.conf")
    for key in [k for k in env if k.startswith("SLURM_") and k != "SLURM_CONF"]:
        del env[key]
    keep, failed, report = flag("SHADOWCERT_KEEP_SLURM_RUN"), True, {}
    try:
        for d in ("runs", "single"):
            os.makedirs(os.path.join(work, d))
        started = time.monotonic()
        # The daemons without a sanitizer run's preloads (the jobs keep them: sbatch passes its
        # environment on).
        daemon_env = {k: v for k, v in env.items() if k not in ("LD_PRELOAD", "ASAN_OPTIONS", "UBSAN_OPTIONS")}
        up = subprocess.run(["bash", script, "start", "--dir", slurm_dir, "--port", str(free_port_pair())],
                            env=daemon_env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, check=False)
        if up.returncode != 0:
            failed = required
            return skip_or_fail(required, "tools/slurm.sh start exited %d:\n%s" % (up.returncode, up.stdout))
        report["slurm_start_seconds"] = round(time.monotonic() - started, 1)
        print(up.stdout.strip())
        cluster = Cluster(source, work, env)

        # One GL command first: without an EGL device the whole test is a GL skip, as in cli_run.h.
        probe, _ = shadowcert(binary, ["fuzz", "--gl", "--cases", "1", "--triangles", "5", "--gl-size", "8x6",
                                       "--json", "single/probe.json", "--out", "single/probe"], work)
        if probe.returncode == 2 and "EGL" in probe.stdout:
            failed = flag("SHADOWCERT_REQUIRE_GL")
            return skip_or_fail(flag("SHADOWCERT_REQUIRE_GL"), "no EGL device: " + probe.stdout.strip())

        fuzz_array(cluster, binary, work, report)
        bench_array(cluster, binary, work, report)
        failed = False
        print("PASS: %d-task job arrays on a real Slurm, shard %d cancelled mid-run and resubmitted; each merge "
              "equals the single run in every figure but the times:" % (SHARDS, CANCELLED))
        print(json.dumps(report, indent=2))
        return 0
    except Failure as e:
        print("FAIL: %s" % e)
        print("(runs and logs in %s)" % work)
        return 1
    finally:
        subprocess.run(["bash", script, "stop", "--dir", slurm_dir], env=env, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL, check=False)
        if keep:
            print("(kept %s)" % work)
        elif not failed:
            shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main(sys.argv))
