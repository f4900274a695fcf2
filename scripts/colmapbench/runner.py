"""The commands of one method on one scene, each timed, logged and kept: a step whose command and
inputs are as recorded in its marker (STEP.done.json) is not run again, and once a step runs,
every later step of that method runs too."""
import hashlib
import json
import os
import shutil
import subprocess
import time


class StepFailed(RuntimeError):
    pass


SMALL_FILE_BYTES = 1 << 20  # hashed; larger inputs are known by size and modification time


def _inputs_key(inputs):
    """What identifies the inputs: a step is redone when one changed. A small file (pairs.txt,
    rewritten by every run) by its content, a large one (features.h5) by size and time."""
    key = []
    for path in inputs:
        try:
            stat = os.stat(path)
        except FileNotFoundError:
            key.append([path, None, None])
            continue
        if stat.st_size <= SMALL_FILE_BYTES:
            with open(path, "rb") as handle:
                key.append([path, stat.st_size, hashlib.sha1(handle.read()).hexdigest()])
        else:
            key.append([path, stat.st_size, stat.st_mtime_ns])
    return key


class Steps:
    def __init__(self, folder, environment=None, timeout=7200.0):
        self.folder = folder
        self.environment = environment
        self.timeout = timeout
        self.ran = False  # a step ran in this run: every later one runs
        self.seconds = {}
        os.makedirs(folder, exist_ok=True)

    def run(self, name, command, inputs=(), outputs=(), folders=()):
        """Runs `command` (a list) unless its marker says it ran as now; returns its seconds.
        `outputs` (files or folders) are removed first, `folders` emptied. StepFailed with the
        log's tail."""
        marker = os.path.join(self.folder, f"{name}.done.json")
        record = {"command": command, "inputs": _inputs_key(inputs)}
        if not self.ran and os.path.exists(marker):
            with open(marker) as handle:
                done = json.load(handle)
            if done.get("command") == command and done.get("inputs") == record["inputs"] and \
                    all(os.path.exists(path) for path in [*outputs, *folders]):
                self.seconds[name] = done["seconds"]
                return done["seconds"]
        self.ran = True
        for path in outputs:
            if os.path.isdir(path):
                shutil.rmtree(path)
            elif os.path.exists(path):
                os.remove(path)
        for path in folders:
            shutil.rmtree(path, ignore_errors=True)
            os.makedirs(path)
        log = os.path.join(self.folder, f"{name}.log")
        start = time.monotonic()
        with open(log, "w") as handle:
            handle.write(" ".join(command) + "\n")
            handle.flush()
            try:
                result = subprocess.run(command, stdout=handle, stderr=subprocess.STDOUT,
                                        env=self.environment, timeout=self.timeout)
            except subprocess.TimeoutExpired:
                raise StepFailed(f"{name}: no answer in {self.timeout:.0f} s ({log})") from None
        seconds = time.monotonic() - start
        if result.returncode != 0:
            with open(log) as handle:
                tail = handle.read().splitlines()[-5:]
            raise StepFailed(f"{name} exited {result.returncode} ({log}):\n  " + "\n  ".join(tail))
        record["seconds"] = seconds
        with open(marker, "w") as handle:
            json.dump(record, handle)
        self.seconds[name] = seconds
        return seconds
