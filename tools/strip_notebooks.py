"""Strip outputs, execution counts and widget state from notebooks, in place.

Usage: python tools/strip_notebooks.py lessons/*.ipynb
"""
import json
import sys


def strip(path: str) -> bool:
    """Strip one notebook; return True if the file changed."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    nb = json.loads(text)
    for cell in nb["cells"]:
        if cell["cell_type"] == "code":
            cell["outputs"] = []
            cell["execution_count"] = None
        cell.get("metadata", {}).pop("execution", None)
    nb.get("metadata", {}).pop("widgets", None)
    new = json.dumps(nb, indent=1, ensure_ascii=False) + "\n"
    if new != text:
        with open(path, "w", encoding="utf-8") as f:
            f.write(new)
    return new != text


if __name__ == "__main__":
    changed = [p for p in sys.argv[1:] if strip(p)]
    print(f"stripped {len(changed)} of {len(sys.argv) - 1} notebooks")
