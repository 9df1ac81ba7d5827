"""The gallery's freshness: docs/gallery/MANIFEST.json records a digest of the code that draws
the gallery's figures (examples/*.py, problems/paper.py, formopt/report/figures.py) and of the
shipped scenes they solve (formopt/scenes/*.toml: the stride figures were drawn by the trapezoid
scenes for a day after the scenes moved to Hermite-Simpson, 2026-11-28) when
`make gallery` redraws them. tests/test_docs.py recomputes it: a figure drawn by older code
fails the test (digests, not file times, which a clone resets).

    python docs/gallery_manifest.py write     # after redrawing (make gallery does it)
    python docs/gallery_manifest.py check     # exit 1 when the gallery is stale
"""

import hashlib
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
GALLERY = ROOT / "docs" / "gallery"
MANIFEST = GALLERY / "MANIFEST.json"


def sources() -> list[Path]:
    """The files whose code draws the gallery, and the scenes it solves."""
    return (sorted(ROOT.glob("examples/*.py")) + [ROOT / "problems" / "paper.py", ROOT / "formopt" / "report" / "figures.py"]
            + sorted(ROOT.glob("formopt/scenes/*.toml")))


def digest() -> dict[str, str]:
    """{repository path: sha256 of its text (line endings normalised)}."""
    return {str(p.relative_to(ROOT)): hashlib.sha256(p.read_text().replace("\r\n", "\n").encode()).hexdigest()
            for p in sources()}


def stale() -> list[str]:
    """The drawing sources changed since the gallery was last drawn, and the figures missing."""
    recorded = json.loads(MANIFEST.read_text()) if MANIFEST.exists() else {"sources": {}, "figures": []}
    now = digest()
    changed = [p for p in sorted(set(now) | set(recorded["sources"]))
               if now.get(p) != recorded["sources"].get(p)]
    missing = [f for f in recorded["figures"] if not (GALLERY / f).exists()]
    return changed + [f"docs/gallery/{f} (missing)" for f in missing]


def write() -> None:
    figures = sorted(str(p.relative_to(GALLERY)) for p in GALLERY.rglob("*.png"))
    MANIFEST.write_text(json.dumps({"sources": digest(), "figures": figures}, indent=1) + "\n")
    print(f"wrote {MANIFEST.relative_to(ROOT)}: {len(figures)} figures")


if __name__ == "__main__":
    if sys.argv[1:] == ["write"]:
        write()
    elif sys.argv[1:] == ["check"]:
        out = stale()
        print("\n".join(out) if out else "gallery fresh")
        sys.exit(1 if out else 0)
    else:
        sys.exit(__doc__)
