"""The live processes of this machine, by command line (what the batch tests check is left over)."""
import os


def processes_mentioning(text):
    """{pid: command line} of the live processes whose command line has `text`."""
    found = {}
    for pid in os.listdir("/proc"):
        if not pid.isdigit():
            continue
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as f:
                command = f.read().replace(b"\0", b" ").decode(errors="replace")
        except OSError:
            continue
        if text in command:
            found[int(pid)] = command
    return found
