"""How the bench scripts write their JSON results: whole or not at all."""
import json
import os
import tempfile


def write_json_atomically(path, data, sort_keys=False):
    """Writes data to path through a temporary file in the same folder and a rename, so that a
    failed run never leaves a half-written result; the file is readable by all (0644)."""
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(path)), suffix=".json")
    with os.fdopen(fd, "w") as f:
        json.dump(data, f, indent=1, sort_keys=sort_keys)
        f.write("\n")
    os.chmod(tmp, 0o644)
    os.replace(tmp, path)
