"""Where the project keeps its scratch output."""
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BUILD = ROOT / "build"
GEN = ROOT / "gen"


def build_dir(*parts):
    """A folder under ``build/`` (ignored by git), created on demand."""
    path = BUILD.joinpath(*parts)
    path.mkdir(parents=True, exist_ok=True)
    return path
