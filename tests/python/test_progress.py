"""Progress on stderr (docs/reference/cli.md, "Progress"): plain lines off a terminal,
a redrawn line on one (through a pseudo-terminal), none under --quiet."""
import fcntl
import os
import pty
import re
import select
import struct
import subprocess
import termios

import pytest


def _env(period=None):
    env = dict(os.environ)
    env.pop("RHEODDA_PROGRESS_PERIOD", None)
    if period is not None:
        env["RHEODDA_PROGRESS_PERIOD"] = str(period)
    return env


def _short(root, tmp_path, name, duration):
    """A shipped example with a shorter duration (the same stages and settling)."""
    text = (root / "examples" / name).read_text()
    text, n = re.subn(r"(?m)^(  duration:)\s*[0-9.e+-]+", r"\g<1> " + str(duration), text)
    assert n == 1
    path = tmp_path / name.split("/")[-1]
    path.write_text(text)
    return path


def _run(args, period=None, timeout=300):
    return subprocess.run(args, capture_output=True, text=True, timeout=timeout, env=_env(period))


def test_a_run_off_a_terminal_prints_lines_with_the_stage_time_steps_and_time_left(root, tmp_path, rheodda_binary):
    scene = _short(root, tmp_path, "excavation-stages.yaml", 1.2)
    done = _run([rheodda_binary, "run", str(scene), "-o", str(tmp_path / "out")], period=0)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "\r" not in done.stderr
    lines = [l for l in done.stderr.splitlines() if l.startswith("rheodda run: ")]
    assert len(lines) > 10, done.stderr
    assert lines[0].startswith("rheodda run: start, settling, t = 0 of 1.2 s, step 0"), lines[0]
    assert lines[-1].startswith("rheodda run: completed, stage 'weaken': "), lines[-1]
    for l in lines:
        assert re.search(r", t = [0-9.e+-]+ of 1\.2 s", l) and re.search(r", step [0-9]+", l), l
    # While settling: the stage, no share of the simulated time, no time left but when it ends at the latest.
    settling = [l for l in lines[1:-1] if ": settling, " in l or l.startswith("rheodda run: settling, ")]
    assert settling and all("%" not in l and "time left: known once the settling stage ends" in l for l in settling)
    assert any(l.startswith("rheodda run: stage 'dig': settling, ") for l in lines), lines
    # After it: the share and the time left (or its measure beginning).
    after = [l for l in lines[1:-1] if "settling" not in l]
    assert after and all(re.search(r"\([0-9.]+ %\)", l) and "time left" in l for l in after), after
    # The summary stays on stdout.
    assert "completed at t = 1.2 of 1.2 s" in done.stdout


def test_off_a_terminal_lines_come_at_most_every_period(root, tmp_path, rheodda_binary):
    scene = _short(root, tmp_path, "sliding-block.yaml", 0.1)
    done = _run([rheodda_binary, "run", str(scene), "-o", str(tmp_path / "out")])
    assert done.returncode == 0, done.stdout + done.stderr
    lines = [l for l in done.stderr.splitlines() if l.startswith("rheodda run: ")]
    # A run shorter than 10 s: its start and its end.
    assert len(lines) == 2 and lines[0].startswith("rheodda run: start, ") and \
        lines[1].startswith("rheodda run: completed, "), done.stderr


def test_quiet_prints_no_progress(root, tmp_path, rheodda_binary):
    scene = _short(root, tmp_path, "sliding-block.yaml", 0.1)
    done = _run([rheodda_binary, "run", str(scene), "-o", str(tmp_path / "out"), "--quiet"], period=0)
    assert done.returncode == 0, done.stdout + done.stderr
    assert done.stderr == ""
    assert "completed at t = 0.1 of 0.1 s" in done.stdout


def _on_a_terminal(args, columns, timeout=300):
    """Runs `args` with stderr on a pseudo-terminal `columns` wide; returns (exit code, what it wrote there)."""
    main, sub = pty.openpty()
    fcntl.ioctl(sub, termios.TIOCSWINSZ, struct.pack("HHHH", 24, columns, 0, 0))
    p = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=sub, env=_env(), stdin=subprocess.DEVNULL)
    os.close(sub)
    out = b""
    while True:
        ready, _, _ = select.select([main], [], [], timeout)
        if not ready:
            p.kill()
            pytest.fail("no output for {} s".format(timeout))
        try:
            chunk = os.read(main, 65536)
        except OSError:  # EIO: the process closed the terminal
            break
        if not chunk:
            break
        out += chunk
    p.stdout.read()
    code = p.wait(timeout)
    os.close(main)
    return code, out.decode()


def test_on_a_terminal_one_line_is_redrawn_in_place(root, tmp_path, rheodda_binary):
    scene = _short(root, tmp_path, "excavation-stages.yaml", 0.6)
    code, err = _on_a_terminal([rheodda_binary, "run", str(scene), "-o", str(tmp_path / "out")], columns=60)
    assert code == 0, err
    # Each update begins with \r and clears what is left of the line; one newline ends the display.
    assert err.count("\r") >= 2 and "\033[K" in err
    progress = err.replace("\r\n", "\n").split("\n")[0]
    states = [s.replace("\033[K", "") for s in progress.split("\r") if s]
    assert states[0].startswith("start  settling  t = 0 of 0.6 s  step 0"), states
    assert states[-1].startswith("completed  stage '"), states
    # Cut to the terminal's width (less one column): a line that wrapped could not be redrawn.
    assert all(len(s) <= 59 for s in states) and len(states[-1]) == 59, states
    assert "rheodda run:" not in err  # no plain lines on a terminal


def test_study_fit_and_generate_show_progress_off_a_terminal(root, tmp_path, rheodda_binary):
    fit = _run([rheodda_binary, "fit", str(root / "examples/creep-data/table1-row1.csv"), "--law", "all",
                "--stress", "0.232", "--units", "MPa, mm, h"], period=0)
    assert fit.returncode == 0, fit.stderr
    lines = [l for l in fit.stderr.splitlines() if l.startswith("rheodda fit --law all: ")]
    # The phase's line is drawn by a timer thread: which laws it catches depends on how fast each
    # fit is (a law fitted within the thread's first wake is never shown), not which come first.
    assert lines and re.search(r"law [0-9]+ of [0-9]+ \(", lines[0]), fit.stderr
    assert re.search(r"rheodda fit --law all: [0-9]+ laws: done in [0-9]", lines[-1]), lines
    quiet = _run([rheodda_binary, "fit", str(root / "examples/creep-data/table1-row1.csv"), "--law", "all",
                  "--stress", "0.232", "--units", "MPa, mm, h", "-q"], period=0)
    assert quiet.returncode == 0 and quiet.stderr == "" and quiet.stdout == fit.stdout

    gen = _run([rheodda_binary, "generate", str(root / "examples/rockmass/tunnel.yaml"), "-o",
                str(tmp_path / "tunnel.yaml")], period=0)
    assert gen.returncode == 0, gen.stderr
    assert "rheodda generate: cutting the rock mass" in gen.stderr and "done in" in gen.stderr, gen.stderr

    study = tmp_path / "study.yaml"
    study.write_text("scene: {}\nset: {{analysis.duration: 0.05, analysis.output_interval: 0.01}}\n"
                     "outputs: [centre.u]\ntimes: [0.05]\ncases:\n  - {{name: a}}\n"
                     "  - {{name: b, set: {{joint_sets.slope.friction_angle: 5}}}}\n".format(
                         root / "examples" / "sliding-block.yaml"))
    st = _run([rheodda_binary, "study", str(study), "-o", str(tmp_path / "study"), "-j", "1", "--no-plot"], period=0)
    assert st.returncode == 0, st.stdout + st.stderr
    assert re.search(r"^\[1/2\] a: completed \(", st.stderr, re.M), st.stderr
    states = [l for l in st.stderr.splitlines() if l.startswith("rheodda study: ")]
    assert states[0].startswith("rheodda study: start, 2 cases, 1 at a time"), states
    assert states[-1].startswith("rheodda study: end, 2 of 2 cases done"), states
    # Each case's own progress lines are in its log.
    assert "rheodda run: completed, " in (tmp_path / "study" / "cases" / "a" / "log.txt").read_text()
    quiet = _run([rheodda_binary, "study", str(study), "-o", str(tmp_path / "study-q"), "-j", "1", "--no-plot",
                  "--quiet"], period=0)
    assert quiet.returncode == 0 and quiet.stderr == "", quiet.stderr
