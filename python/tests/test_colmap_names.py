"""Image names that are not UTF-8 (file names are bytes on Linux) in the COLMAP export: stored as
their bytes, as COLMAP itself stores them, read back byte for byte by sqlite3 and by COLMAP."""
import os
import shutil
import sqlite3
import subprocess

import pytest

from conftest import sample_path

LATIN1 = os.fsdecode(b"caf\xe9.png")  # "café.png" in Latin-1: not UTF-8


def run_cli(cli, *args):
    """As conftest's, with output that may hold the name's bytes."""
    result = subprocess.run([cli, *map(str, args)], capture_output=True, text=True, errors="backslashreplace")
    assert result.returncode == 0, result.stderr
    return result


def test_names_not_utf8_read_back_as_their_bytes(cli, tmp_path):
    images = tmp_path / "images"
    images.mkdir()
    shutil.copy(sample_path("graf", 1), images / LATIN1)
    shutil.copy(sample_path("graf", 2), images / "graf2.png")
    run_cli(cli, "extract", "--batch", images, "-o", tmp_path / "features.h5", "--format", "h5", "--features", 500)
    pairs = tmp_path / "pairs.txt"
    pairs.write_bytes(b"caf\xe9.png graf2.png\n")
    run_cli(cli, "match", "--pairs", pairs, "--features", tmp_path / "features.h5", "-o", tmp_path / "matches.h5")
    database = tmp_path / "database.db"
    export = run_cli(cli, "colmap", "--features", tmp_path / "features.h5", "--matches", tmp_path / "matches.h5",
                     "--pairs", pairs, "-o", database)
    assert "1 image name(s) are not UTF-8 (the first: 'caf\\xE9.png')" in export.stderr, export.stderr
    assert "text_factory = bytes" in export.stderr

    db = sqlite3.connect(database)
    with pytest.raises(sqlite3.OperationalError, match="decode"):  # what the note is for
        db.execute("SELECT name FROM images").fetchall()
    db.text_factory = bytes
    names = dict(db.execute("SELECT name, image_id FROM images"))
    assert names == {b"caf\xe9.png": 1, b"graf2.png": 2}
    assert db.execute("SELECT typeof(name) FROM images").fetchall() == [(b"text",), (b"text",)]  # COLMAP's column type

    colmap = shutil.which("colmap")
    if colmap is None:
        pytest.skip("colmap is not installed: checked by sqlite3 only")
    # COLMAP reads the name back and finds the pair by it: the matches are verified.
    subprocess.run([colmap, "matches_importer", "--database_path", database, "--match_list_path", pairs,
                    "--match_type", "pairs", "--SiftMatching.use_gpu", "0", "--SiftMatching.num_threads", "1"],
                   check=True, capture_output=True, env=dict(os.environ, QT_QPA_PLATFORM="offscreen"))
    assert db.execute("SELECT COUNT(*) FROM two_view_geometries WHERE rows > 0").fetchone()[0] == 1
