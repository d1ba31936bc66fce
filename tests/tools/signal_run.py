#!/usr/bin/env python3
"""Runs a command, sends it a signal once it has used a given processor time, and reports how
promptly it stopped, in terms that do not depend on the machine's load: the processor time the
command spent after the signal (the work it did before it saw the stop), beside the wall time
(which load stretches; a bound on it only catches a hang).

    signal_run.py REPORT SIGNAL CPU_SECONDS COMMAND [ARGS...]

The command runs with SIGNAL's default disposition (the suite may run with it ignored: nohup,
a background shell) and the caller's standard streams. Once its processor time (all its threads,
/proc/PID/stat) has grown by CPU_SECONDS it gets SIGNAL; a command still running 120 s of wall
time later is killed (SIGKILL). REPORT gets one line:
    status=N wall=S cpu_after=S cpu_before=S early=0|1
status as a shell gives it (128 + the signal for a command it killed), early=1 when the command
ended before the signal was sent. The exit status is the command's, as the shell's."""
import os
import signal
import subprocess
import sys
import time


def cpu(pid):
    """Processor seconds of the process, user and system, all its threads."""
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def main(argv):
    if len(argv) < 5:
        sys.stderr.write(__doc__)
        return 2
    report, name, budget, command = argv[1], argv[2], float(argv[3]), argv[4:]
    sig = getattr(signal, "SIG" + name)
    p = subprocess.Popen(command, preexec_fn=lambda: signal.signal(sig, signal.SIG_DFL))
    early, before = 1, 0.0
    while True:
        pid, status, usage = os.wait4(p.pid, os.WNOHANG)
        if pid:
            break
        try:
            before = cpu(p.pid)
        except (OSError, ValueError):  # ended between the two reads
            continue
        if before >= budget:
            early = 0
            t0 = time.monotonic()
            os.kill(p.pid, sig)
            while True:
                pid, status, usage = os.wait4(p.pid, os.WNOHANG)
                if pid:
                    break
                if time.monotonic() - t0 > 120:
                    os.kill(p.pid, signal.SIGKILL)
                    pid, status, usage = os.wait4(p.pid, 0)
                    break
                time.sleep(0.005)
            wall = time.monotonic() - t0
            break
        time.sleep(0.01)
    if early:
        wall = 0.0
    after = usage.ru_utime + usage.ru_stime - before if not early else 0.0
    rc = 128 + os.WTERMSIG(status) if os.WIFSIGNALED(status) else os.WEXITSTATUS(status)
    with open(report, "w") as f:
        f.write("status=%d wall=%.3f cpu_after=%.3f cpu_before=%.3f early=%d\n"
                % (rc, wall, max(after, 0.0), before, early))
    return rc


if __name__ == "__main__":
    sys.exit(main(sys.argv))
