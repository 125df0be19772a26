"""The training loop of docs/python.md runs (python/examples/train_go_to_ball.py)."""

import os
import subprocess
import sys

EXAMPLE = os.path.join(os.path.dirname(__file__), "..", "examples", "train_go_to_ball.py")


def test_the_docs_training_loop_runs():
    result = subprocess.run([sys.executable, EXAMPLE, "2"], capture_output=True, text=True,
                            timeout=300)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert [line.split(":")[0] for line in lines] == ["iteration 0", "iteration 1"]


def test_the_docs_page_shows_the_example_as_it_is():
    docs = os.path.join(os.path.dirname(__file__), "..", "..", "docs", "python.md")
    with open(EXAMPLE) as example, open(docs) as page:
        assert example.read().strip() in page.read()
