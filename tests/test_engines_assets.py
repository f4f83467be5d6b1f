"""pitheorem.engines.fileformats.assets: a saved model's asset files, copied beside it on request.

The writers' use of it (a copy that loads after its originals are gone) is tested in
test_engines_mjcf and test_engines_urdf.
"""

from __future__ import annotations

from pitheorem.engines.fileformats.assets import AssetCopies, assets_folder


def test_the_folder_is_named_after_the_written_file():
    assert assets_folder("/x/out/hopper_g10.xml").as_posix() == "/x/out/hopper_g10_assets"
    assert assets_folder("arm.urdf").name == "arm_assets"


def test_copied_assets_of_the_same_name_from_two_folders_are_kept_apart(tmp_path):
    for side, text in (("left", "L"), ("right", "R")):
        (tmp_path / side).mkdir()
        (tmp_path / side / "foot.stl").write_text(text)
    copies = AssetCopies(tmp_path / "out")
    left, right = copies.copy(tmp_path / "left" / "foot.stl"), copies.copy(tmp_path / "right" / "foot.stl")
    assert (left.read_text(), right.read_text()) == ("L", "R")
    assert copies.copy(tmp_path / "left" / "foot.stl") == left  # once per file
    # a second writer of the same folder reuses an identical copy and never overwrites a different one
    again = AssetCopies(tmp_path / "out")
    assert again.copy(tmp_path / "right" / "foot.stl") != left
    assert left.read_text() == "L"
