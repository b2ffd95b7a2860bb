"""Asking a remote again until it answers: the answer is returned as soon as there is one, and
the caller's stop ends the asking between two questions."""

from __future__ import annotations

from kame.node.remote_poll import poll_remote


def test_the_first_answer_is_returned_and_nothing_more_is_asked() -> None:
    answers = iter([None, None, "here", "again"])
    asked: list[int] = []

    def ask() -> str | None:
        asked.append(1)
        return next(answers)

    waits: list[float] = []
    assert poll_remote(ask, lambda period: bool(waits.append(period)), period=0.25) == "here"
    assert len(asked) == 3 and waits == [0.25, 0.25]


def test_a_stop_between_two_questions_ends_the_wait_with_none() -> None:
    asked: list[int] = []

    def ask() -> None:
        asked.append(1)

    assert poll_remote(ask, lambda period: len(asked) == 2) is None
    assert len(asked) == 2
