"""The GIL is released during extraction: two Python threads are inside the engine at once.

The engine-side rendezvous (python/extraction_rendezvous.hpp) lets an extraction return only
once two extractions are inside the GIL-free section together, which is impossible if either
holds the GIL; its timeout only guards against a hang, nothing is timed."""
import threading

import pytest

import aief
from conftest import assert_same_features, read_unchanged, sample_path


@pytest.fixture
def rendezvous():
    def arm(parties, timeout_s=60.0):
        aief._aief._arm_extraction_rendezvous(parties, timeout_s)
    yield arm
    aief._aief._arm_extraction_rendezvous(0, 0.0)


def test_two_threads_extract_at_once(rendezvous):
    images = [read_unchanged(sample_path("graf", 1)), read_unchanged(sample_path("boat", 1))]
    expected = [aief.Extractor().extract(image) for image in images]
    rendezvous(2)
    results, errors = [None, None], []

    def work(i):
        try:
            results[i] = aief.Extractor().extract(images[i])
        except Exception as e:  # reported below, not lost in the thread
            errors.append(e)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert errors == []
    for result, reference in zip(results, expected):
        assert_same_features(result, reference)


def test_the_rendezvous_can_fail(rendezvous):
    rendezvous(2, 0.05)  # one thread alone can never meet a second
    with pytest.raises(aief.Error, match="1 of 2 extractions"):
        aief.Extractor().extract(read_unchanged(sample_path("leuven", 1)))


def test_one_extractor_shared_by_threads_gives_the_serial_answers():
    image = read_unchanged(sample_path("leuven", 1))
    extractor = aief.Extractor()
    expected = extractor.extract(image)
    results = []
    threads = [threading.Thread(target=lambda: results.append(extractor.extract(image))) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(results) == 4
    for result in results:
        assert_same_features(result, expected)


# threads= above what the process may use let TBB print its raw "TBB Warning: ... request for N
# workers is ignored" to stderr; the CLI notes it and uses what there is (parallel/scheduler.hpp).
def test_more_threads_than_the_machine_runs_are_noted_and_capped(capfd):
    with pytest.warns(UserWarning) as caught:
        extractor = aief.Extractor(threads=256)
    [note] = [str(w.message) for w in caught]
    available = extractor.options["threads"]
    assert note == f"threads 256 is more than the {available} hardware threads this process may use; using {available}"
    assert 1 <= available < 256
    capfd.readouterr()
    assert_same_features(extractor.extract(read_unchanged(sample_path("graf", 1))),
                         aief.Extractor(threads=1).extract(read_unchanged(sample_path("graf", 1))))
    assert "TBB Warning" not in capfd.readouterr().err
