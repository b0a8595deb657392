#!/usr/bin/python3
"""The helpers of app/bench/soak.sh (the design is in its header): one sub-command each.

  soak_check.py steps CHECKPOINT            the checkpoint's step count and particle count
  soak_check.py rate LOG                    steps per second from a `drumlab run` report
  soak_check.py drive ...                   the killed run: segments killed at random moments
  soak_check.py memwatch --pid P --out CSV  samples VmRSS / RssAnon of a process until it exits
  soak_check.py check ...                   one scene's checks into DIR/result.json
  soak_check.py table DIR...                the summary table; exit 1 if a check failed

Needs python3-h5py and python3-numpy (Debian 12; tomllib is Python 3.11's).
"""
import argparse
import glob
import json
import math
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import time
import tomllib

import h5py
import numpy as np

# Relative drift of the liquid allowed (the issue: conserved to 1e-12).
LIQUID_TOLERANCE = 1e-12
# Memory flat: the late sample may exceed the early one by at most this share or this many bytes,
# whichever is larger (the XDMF sidecar's text grows by a few hundred bytes a frame, by design).
MEMORY_SHARE = 0.01
MEMORY_BYTES = 2 * 1024 * 1024


def checkpoint_steps(path):
    with h5py.File(path, "r") as f:
        return int(f.attrs["steps"]), int(f["particles/radius"].shape[0])


def cmd_steps(a):
    steps, n = checkpoint_steps(a.checkpoint)
    print(steps, n)


def cmd_rate(a):
    text = open(a.log, encoding="utf-8", errors="replace").read()
    steps = re.search(r"^steps\s+(\d+) \(dt", text, re.M)
    wall = re.search(r"^wall time\s+[0-9.]+ s \(stepping ([0-9.]+) s", text, re.M)
    if not steps or not wall or float(wall.group(1)) <= 0:
        sys.exit(f"soak_check rate: no 'steps' / 'wall time' lines in {a.log}")
    print(f"{int(steps.group(1)) / float(wall.group(1)):.6g}")


# --- the killed run ----------------------------------------------------------------------------


def leftover_tmps(ckpt):
    return sorted(glob.glob(glob.escape(ckpt) + ".tmp-*"))


def wait_for_write(p, ckpt, give_up):
    """Polls (0.5 ms) for the checkpoint's temporary file; True once it is there."""
    d, prefix = os.path.dirname(ckpt) or ".", os.path.basename(ckpt) + ".tmp-"
    while time.time() < give_up and p.poll() is None:
        with os.scandir(d) as it:
            if any(e.name.startswith(prefix) for e in it):
                return True
        time.sleep(0.0005)
    return False


def cmd_drive(a):
    rng = random.Random(a.seed)
    ckpt, seg_in = a.ckpt, a.ckpt + ".in.h5"
    shutil.copyfile(a.init, ckpt)
    s0, _ = checkpoint_steps(a.init)
    target = s0 + a.steps
    log = open(a.log, "a", encoding="utf-8")
    rec = {"target_step": target, "segments": 0, "kills": 0, "kills_aimed_at_write": 0,
           "kills_in_write": 0, "tmp_files_left": [], "kill_times_s": [], "ok": False,
           "error": ""}
    t_start = time.time()

    def save():
        with open(a.out, "w", encoding="utf-8") as f:
            json.dump(rec, f, indent=1)

    while True:
        try:
            done, _ = checkpoint_steps(ckpt)  # the file under its final name, never a .tmp
        except Exception as e:  # noqa: BLE001 - any failure to read is the finding
            rec["error"] = f"checkpoint unreadable after kill {rec['kills']}: {e}"
            break
        if done == target:
            rec["ok"] = True
            break
        if done > target:
            rec["error"] = f"checkpoint at step {done}, past the target {target}"
            break
        shutil.copyfile(ckpt, seg_in)
        cmd = [a.bin, "run", a.scene, "--threads", "1", "--restart", seg_in, "--steps",
               str(target - done), "--checkpoint", ckpt, "--checkpoint-every", str(a.every)]
        # Both draws every segment, so the schedule follows from the seed alone.
        delay = rng.uniform(0.25, 1.75) * a.kill_mean
        aim = rng.random() < a.write_kills
        print(f"--- segment {rec['segments'] + 1} from step {done}: {' '.join(cmd)}", file=log,
              flush=True)
        p = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT,
                             env=dict(os.environ, OMP_NUM_THREADS="1"))
        # soak.sh stopped (Ctrl-C, TERM): take this segment's process along.
        signal.signal(signal.SIGTERM, lambda *_, p=p: (p.kill(), sys.exit(1)))
        rec["segments"] += 1
        seg_start = time.time()
        killed = False
        try:
            p.wait(timeout=max(0.0, min(seg_start + delay, a.deadline) - time.time()))
        except subprocess.TimeoutExpired:
            if time.time() < a.deadline:  # no kills after the deadline: the run may end
                if aim:
                    rec["kills_aimed_at_write"] += 1
                    wait_for_write(p, ckpt, min(time.time() + 3 * a.kill_mean, a.deadline))
                if p.poll() is None:
                    p.send_signal(signal.SIGKILL)
                    killed = True
        rc = p.wait()
        if killed and rc == -signal.SIGKILL:
            rec["kills"] += 1
            rec["kill_times_s"].append(round(time.time() - t_start, 2))
            tmps = leftover_tmps(ckpt)
            print(f"--- killed after {time.time() - seg_start:.2f} s"
                  f"{' (aimed at a write)' if aim else ''}; left: {tmps or 'no .tmp'}",
                  file=log, flush=True)
            if tmps:
                rec["kills_in_write"] += 1
                rec["tmp_files_left"] += [os.path.basename(t) for t in tmps]
                for t in tmps:
                    os.remove(t)
        elif rc != 0:
            rec["error"] = f"segment {rec['segments']} exited with {rc} (see {a.log})"
            break
        save()
    try:
        os.remove(seg_in)
    except FileNotFoundError:
        pass
    rec["wall_s"] = round(time.time() - t_start, 1)
    save()
    print(f"drive {a.scene}: {rec['segments']} segments, {rec['kills']} kills "
          f"({rec['kills_in_write']} during a checkpoint write), "
          f"{'reached' if rec['ok'] else 'FAILED:'} {rec['error'] or target}")
    sys.exit(0 if rec["ok"] else 1)


# --- memory ------------------------------------------------------------------------------------


def cmd_memwatch(a):
    t0 = time.time()
    with open(a.out, "w", encoding="utf-8") as out:
        out.write("seconds,vm_rss_kb,rss_anon_kb\n")
        while True:
            try:
                text = open(f"/proc/{a.pid}/status", encoding="ascii").read()
            except (FileNotFoundError, ProcessLookupError):
                break
            fields = dict(re.findall(r"^(\w+):\s+(\d+) kB", text, re.M))
            if "RssAnon" not in fields or text.find("State:\tZ") >= 0:
                break
            out.write(f"{time.time() - t0:.2f},{fields['VmRSS']},{fields['RssAnon']}\n")
            out.flush()
            time.sleep(a.interval)


def memory_check(csv):
    rows = np.loadtxt(csv, delimiter=",", skiprows=1, ndmin=2)
    if rows.shape[0] < 4:
        return {"ok": False, "note": f"{rows.shape[0]} memory samples"}
    t, anon = rows[:, 0], rows[:, 2] * 1024.0
    duration = t[-1]
    mark = min(3600.0, duration / 2)
    window = max(0.1 * duration, 1e-9)
    # The peak in a window before the mark against the peak in the last window before the end:
    # both hold frame writes; the final checkpoint's image is written after the last window.
    early = anon[(t > mark - window) & (t <= mark)]
    late = anon[(t > duration - 2 * window) & (t <= duration - window)]
    if early.size == 0 or late.size == 0:
        return {"ok": False, "note": "too few memory samples in the windows"}
    e, l = float(early.max()), float(late.max())
    allowed = max(MEMORY_SHARE * e, MEMORY_BYTES)
    return {"ok": l - e <= allowed, "mark_s": mark, "end_s": duration, "early_bytes": e,
            "late_bytes": l, "allowed_growth_bytes": allowed, "samples": int(rows.shape[0])}


# --- checks ------------------------------------------------------------------------------------


def compare_checkpoints(a_path, b_path):
    """Every attribute and dataset of the two files, bit for bit."""
    diffs, count = [], [0]

    def same(x, y):
        x, y = np.asarray(x), np.asarray(y)
        return x.dtype == y.dtype and x.shape == y.shape and x.tobytes() == y.tobytes()

    def attrs(oa, ob, path):
        for k in sorted(set(oa.attrs) | set(ob.attrs)):
            count[0] += 1
            if k not in oa.attrs or k not in ob.attrs or not same(oa.attrs[k], ob.attrs[k]):
                diffs.append(f"{path}@{k}")

    def walk(ga, gb, path):
        attrs(ga, gb, path or "/")
        for k in sorted(set(ga) | set(gb)):
            if k not in ga or k not in gb:
                diffs.append(f"{path}/{k} (only in one)")
                continue
            if isinstance(ga[k], h5py.Group):
                walk(ga[k], gb[k], f"{path}/{k}")
            else:
                count[0] += 1
                if not same(ga[k][()], gb[k][()]):
                    diffs.append(f"{path}/{k}")
                attrs(ga[k], gb[k], f"{path}/{k}")

    with h5py.File(a_path, "r") as fa, h5py.File(b_path, "r") as fb:
        walk(fa, fb, "")
        res = {"ok": not diffs, "compared": count[0], "differ": diffs[:10], "empty_contacts": 0}
        if diffs and all(d.startswith("/contacts/") for d in diffs):
            same_pairs, empty = same_contacts(fa["contacts"], fb["contacts"])
            if same_pairs:
                res.update(ok=True, differ=[], empty_contacts=empty)
    return res


def contact_pairs(g):
    """The contact list as {(row, partner): bytes of history and state}, without empty entries."""
    row_start, col = g["row_start"][()], g["col"][()]
    parts = [g[k][()].reshape(len(col), -1) for k in ("history", "state") if k in g]
    data = np.concatenate(parts, axis=1) if parts else np.zeros((len(col), 0))
    rows = np.repeat(np.arange(len(row_start) - 1), np.diff(row_start).astype(np.int64))
    out, empty = {}, set()
    for i, j, d in zip(rows.tolist(), col.tolist(), data):
        if not np.any(d != 0.0):
            empty.add((i, j))
            continue
        out[(i, j)] = d.tobytes()
    return out, empty


def same_contacts(ga, gb):
    """The two contact lists hold the same contacts bit for bit once the entries with zero history
    and state are dropped: those carry nothing (a pair found anew starts from zero) and which of
    them a list holds depends on when it was last rebuilt, i.e. on the restarts."""
    if set(ga) != set(gb):
        return False, 0
    pa, ea = contact_pairs(ga)
    pb, eb = contact_pairs(gb)
    return pa == pb, len(ea ^ eb)


def liquid_check(obs_csv):
    with open(obs_csv, encoding="utf-8") as f:
        head = f.readline().strip().split(",")
    rows = np.loadtxt(obs_csv, delimiter=",", skiprows=1, ndmin=2)
    col = {n: rows[:, head.index(n)] for n in head}
    # What the particles and walls hold, plus what the spray has in the air, lost or on the wall,
    # less what it has sprayed: constant when nothing is created or destroyed.
    total = (col["free_liquid"] + col["bridge_liquid"] + col["wall_liquid"] +
             col["airborne_liquid"] + col["lost_liquid"] + col["wall_film_liquid"] -
             col["sprayed_liquid"])
    if not np.all(np.isfinite(total)):
        return {"ok": False, "dry": False, "drift": float("nan"), "frames": int(rows.shape[0])}
    if total[0] == 0.0 and np.all(total == 0.0):
        return {"ok": True, "dry": True, "drift": 0.0, "frames": int(rows.shape[0])}
    drift = float(np.max(np.abs(total - total[0])) / abs(total[0]))
    return {"ok": drift <= LIQUID_TOLERANCE, "dry": False, "drift": drift,
            "initial_m3": float(total[0]), "frames": int(rows.shape[0])}


def energy_check(series, scene_file):
    scene = tomllib.load(open(scene_file, "rb"))
    g = float(np.linalg.norm(scene.get("gravity", [0.0, -9.81, 0.0])))
    radius_drum = 0.5 * float(scene["drum"]["diameter"])
    omega = abs(float(scene["drum"].get("omega", 0.0)))
    density = float(scene["material"]["density"])
    ke_max, bound, finite, frames = 0.0, None, True, 0
    with h5py.File(series, "r") as f:
        for name in sorted(k for k in f if k.startswith("frame_")):
            fr = f[name]
            v, w, r = fr["velocity"][()], fr["omega"][()], fr["radius"][()]
            m = fr["mass"][()] if "mass" in fr else density * 4.0 / 3.0 * math.pi * r**3
            finite = finite and bool(np.all(np.isfinite(v)) and np.all(np.isfinite(w)))
            ke = 0.5 * np.sum(m * np.sum(v * v, axis=1)) + \
                0.5 * np.sum(0.4 * m * r * r * np.sum(w * w, axis=1))
            ke_max = max(ke_max, float(ke)) if np.isfinite(ke) else float("inf")
            if bound is None:
                # The whole bed lifted by one drum diameter plus the bed turning with the wall:
                # no avalanche in a closed drum can give the particles more.
                total_mass = float(np.sum(m))
                bound = total_mass * (g * 2.0 * radius_drum + 0.5 * (omega * radius_drum) ** 2)
            frames += 1
    if frames == 0:
        return {"ok": False, "frames": 0, "max_j": float("nan"), "bound_j": float("nan")}
    return {"ok": finite and ke_max <= bound, "finite": finite, "frames": frames,
            "max_j": ke_max, "bound_j": bound}


def cmd_check(a):
    res = {"scene": a.name, "steps": a.steps}
    try:
        drive = json.load(open(os.path.join(a.dir, "drive.json"), encoding="utf-8"))
    except FileNotFoundError:
        drive = {"ok": False, "kills": 0, "kills_in_write": 0, "error": "no drive.json"}
    res["drive"] = drive
    ref, killed = os.path.join(a.dir, "reference.h5"), os.path.join(a.dir, "killed.h5")
    try:
        res["identical"] = compare_checkpoints(ref, killed) if drive["ok"] else \
            {"ok": False, "differ": ["the killed run did not finish"]}
    except Exception as e:  # noqa: BLE001
        res["identical"] = {"ok": False, "differ": [str(e)]}
    for key, fn in (("liquid", lambda: liquid_check(os.path.join(a.dir, "observables.csv"))),
                    ("energy", lambda: energy_check(os.path.join(a.dir, "series.h5"), a.scene)),
                    ("memory", lambda: memory_check(os.path.join(a.dir, "memory.csv")))):
        try:
            res[key] = fn()
        except Exception as e:  # noqa: BLE001
            res[key] = {"ok": False, "note": f"{type(e).__name__}: {e}"}
    res["ok"] = all(res[k]["ok"] for k in ("identical", "liquid", "energy", "memory")) and \
        drive["ok"]
    with open(os.path.join(a.dir, "result.json"), "w", encoding="utf-8") as f:
        json.dump(res, f, indent=1)
    if not res["identical"]["ok"]:
        print(f"{a.name}: final states differ: {res['identical'].get('differ')}")


def ident(r):
    if not r["ok"]:
        return "NO"
    return f"yes ({r['empty_contacts']} empty contacts)" if r.get("empty_contacts") else "yes"


def cmd_table(a):
    mib = 1.0 / (1024 * 1024)
    head = ("scene", "steps", "kills (in write)", "identical", "liquid drift", "max KE / bound",
            "heap early -> end", "result")
    rows, all_ok = [], True
    for d in a.dirs:
        try:
            r = json.load(open(os.path.join(d, "result.json"), encoding="utf-8"))
        except FileNotFoundError:
            rows.append((os.path.basename(d), "-", "-", "-", "-", "-", "-", "FAIL (no result)"))
            all_ok = False
            continue
        dr, li, en, me = r["drive"], r["liquid"], r["energy"], r["memory"]
        liquid = "dry" if li.get("dry") else (f"{li['drift']:.2e}" if "drift" in li else "?")
        energy = (f"{en['max_j']:.3g} / {en['bound_j']:.3g} J" if "max_j" in en else
                  en.get("note", "?"))
        memory = (f"{me['early_bytes'] * mib:.1f} -> {me['late_bytes'] * mib:.1f} MiB "
                  f"(t {me['mark_s']:.0f} / {me['end_s']:.0f} s)" if "early_bytes" in me
                  else me.get("note", "?"))
        failed = [k for k in ("identical", "liquid", "energy", "memory") if not r[k]["ok"]]
        if not dr["ok"]:
            failed.insert(0, "killed run")
        all_ok = all_ok and not failed
        rows.append((r["scene"], str(r["steps"]), f"{dr['kills']} ({dr['kills_in_write']})",
                     ident(r["identical"]), liquid, energy, memory,
                     "ok" if not failed else "FAIL: " + ", ".join(failed)))
    widths = [max(len(x[i]) for x in [head] + rows) for i in range(len(head))]
    line = lambda cells: "| " + " | ".join(c.ljust(w) for c, w in zip(cells, widths)) + " |"
    print(line(head))
    print("|" + "|".join("-" * (w + 2) for w in widths) + "|")
    for row in rows:
        print(line(row))
    print("identical: every attribute and dataset of the final checkpoints bit for bit; the contact "
          "lists without their empty entries (zero history and state), which depend on the "
          "restarts")
    print(f"liquid: relative drift <= {LIQUID_TOLERANCE:g}; energy: kinetic (+ rotational) never "
          f"above M (g D + (omega R)^2 / 2), all finite; heap: RssAnon, end <= early + "
          f"max({MEMORY_SHARE:.0%}, {MEMORY_BYTES * mib:.0f} MiB)")
    sys.exit(0 if all_ok else 1)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("steps")
    p.add_argument("checkpoint")
    p.set_defaults(fn=cmd_steps)
    p = sub.add_parser("rate")
    p.add_argument("log")
    p.set_defaults(fn=cmd_rate)
    p = sub.add_parser("drive")
    for k in ("--bin", "--scene", "--init", "--ckpt", "--log", "--out"):
        p.add_argument(k, required=True)
    p.add_argument("--steps", type=int, required=True)
    p.add_argument("--every", type=int, required=True, help="--checkpoint-every")
    p.add_argument("--kill-mean", type=float, required=True, help="mean seconds to a kill")
    p.add_argument("--write-kills", type=float, default=0.3,
                   help="share of kills that wait for a checkpoint write")
    p.add_argument("--seed", type=int, required=True)
    p.add_argument("--deadline", type=float, required=True, help="epoch seconds: no kill after")
    p.set_defaults(fn=cmd_drive)
    p = sub.add_parser("memwatch")
    p.add_argument("--pid", type=int, required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--interval", type=float, default=2.0)
    p.set_defaults(fn=cmd_memwatch)
    p = sub.add_parser("check")
    for k in ("--name", "--scene", "--dir"):
        p.add_argument(k, required=True)
    p.add_argument("--steps", type=int, required=True)
    p.set_defaults(fn=cmd_check)
    p = sub.add_parser("table")
    p.add_argument("dirs", nargs="+")
    p.set_defaults(fn=cmd_table)
    a = ap.parse_args()
    a.fn(a)


if __name__ == "__main__":
    main()
