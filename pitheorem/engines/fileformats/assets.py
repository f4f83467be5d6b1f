"""The asset files of a written model (meshes, textures, height fields), copied beside it on request.

A saved model names each asset file relative to the written file, so the
folder that holds both can move.  With ``copy_assets`` (``EngineModel.save``,
the command line's ``--copy-assets``) the asset files themselves are copied
into a folder beside the written file, ``<stem>_assets``, and the file names
the copies: the written file and that folder then travel alone.
"""

from __future__ import annotations

import filecmp
import shutil
from pathlib import Path

__all__ = ["AssetCopies", "assets_folder"]


def assets_folder(path) -> Path:
    """The folder beside a written model file that holds its copied assets: ``<stem>_assets``.

    Examples
    --------
    >>> from pitheorem.engines.fileformats.assets import assets_folder
    >>> assets_folder("/tmp/out/hopper_g10.xml").as_posix()
    '/tmp/out/hopper_g10_assets'
    """
    path = Path(path)
    return path.parent / f"{path.stem}_assets"


class AssetCopies:
    """Copies of asset files in one folder, one per source file, each under its own name where it can be.

    Two files of the same name from different folders (``left/foot.stl``,
    ``right/foot.stl``) that differ get ``foot.stl`` and ``foot_2.stl``; one
    file named twice is copied once.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from pitheorem.engines.fileformats.assets import AssetCopies
    >>> tmp = pathlib.Path(tempfile.mkdtemp())
    >>> for side, text in (("left", "L"), ("right", "R")):
    ...     (tmp / side).mkdir()
    ...     _ = (tmp / side / "foot.stl").write_text(text)
    >>> copies = AssetCopies(tmp / "out_assets")
    >>> [copies.copy(tmp / s / "foot.stl").name for s in ("left", "right", "left")]
    ['foot.stl', 'foot_2.stl', 'foot.stl']
    """

    def __init__(self, folder: Path):
        self.folder = Path(folder)
        self._copied: dict[Path, Path] = {}

    def copy(self, source) -> Path:
        """The copy of `source` in the folder (made on the first call), as an absolute path."""
        source = Path(source).resolve()
        if source in self._copied:
            return self._copied[source]
        self.folder.mkdir(parents=True, exist_ok=True)
        target, n = self.folder / source.name, 1
        taken = set(self._copied.values())
        while target in taken or (target.exists() and not filecmp.cmp(source, target, shallow=False)):
            n += 1
            target = self.folder / f"{source.stem}_{n}{source.suffix}"
        if not target.exists():
            shutil.copyfile(source, target)
        self._copied[source] = target.resolve()
        return self._copied[source]
