"""The module's docstrings and messages in its C++ sources (python/*.cpp) are written whole: a text
split over adjacent string literals (to stay within 100 columns) is split at the end of a sentence
or clause, never mid-phrase ("keypoints: aief " / "Features (e.g. ..." read as two broken lines in
the source, and clang-format keeps adjacent literals as they are)."""
import pathlib
import re

SOURCES = sorted(pathlib.Path(__file__).resolve().parent.parent.glob("*.cpp"))
LITERAL = r'"(?:[^"\\\n]|\\.)*"'
ADJACENT = re.compile(LITERAL + r"(?:\s*" + LITERAL + r")+")
# Where a literal may end before the next: a sentence, a clause, a parenthesis, a line.
ENDS = (". ", "; ", ": ", ", ", "? ", "! ", ") ", "\\n")


def splits_mid_phrase(source):
    found = []
    for group in ADJACENT.finditer(source):
        pieces = [literal[1:-1] for literal in re.findall(LITERAL, group.group(0))]
        line = source.count("\n", 0, group.start()) + 1
        for before, after in zip(pieces, pieces[1:]):
            if not (before.endswith(ENDS) or after.startswith("(")):
                found.append(f"line {line}: ...{before[-30:]!r} | {after[:30]!r}...")
    return found


def test_sources_are_found():
    assert any(path.name == "bind_extractor.cpp" for path in SOURCES)


def test_adjacent_literals_split_at_sentence_or_clause_ends():
    broken = {path.name: splits_mid_phrase(path.read_text()) for path in SOURCES}
    assert {name: found for name, found in broken.items() if found} == {}


def test_a_split_mid_phrase_is_found():
    assert splits_mid_phrase('"keypoints: aief "\n  "Features (e.g. from extract())"')
    assert not splits_mid_phrase('"keypoints: "\n  "aief Features"')
