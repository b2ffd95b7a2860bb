"""kame.action's rules as tables: server goal-handle transitions, cancel matching, the client's
CommState machine, the simple client's view and goal id strings (spec §9)."""

from __future__ import annotations

import pytest

from kame.action import (
    TERMINAL,
    CancelRequest,
    CommState,
    InvalidTransition,
    ServerEvent,
    SimpleGoalState,
    SimpleStep,
    Status,
    canceled_by_last_cancel,
    client_goal_id,
    comm_steps,
    generated_goal_id,
    lost_when_unlisted,
    server_transition,
    simple_step,
)

S = Status
E = ServerEvent
C = CommState

# ---------------------------------------------------------------- server (§9.3)

ALLOWED = {
    (E.ACCEPT, S.PENDING): S.ACTIVE,
    (E.ACCEPT, S.RECALLING): S.PREEMPTING,
    (E.REJECT, S.PENDING): S.REJECTED,
    (E.REJECT, S.RECALLING): S.REJECTED,
    (E.CANCEL_REQUEST, S.PENDING): S.RECALLING,
    (E.CANCEL_REQUEST, S.ACTIVE): S.PREEMPTING,
    (E.CANCEL, S.PENDING): S.RECALLED,
    (E.CANCEL, S.RECALLING): S.RECALLED,
    (E.CANCEL, S.ACTIVE): S.PREEMPTED,
    (E.CANCEL, S.PREEMPTING): S.PREEMPTED,
    (E.SUCCEED, S.ACTIVE): S.SUCCEEDED,
    (E.SUCCEED, S.PREEMPTING): S.SUCCEEDED,
    (E.ABORT, S.ACTIVE): S.ABORTED,
    (E.ABORT, S.PREEMPTING): S.ABORTED,
}
SERVER_STATES = [s for s in Status if s is not S.LOST]


@pytest.mark.parametrize("event", list(ServerEvent), ids=lambda e: e.name)
@pytest.mark.parametrize("status", SERVER_STATES, ids=lambda s: s.name)
def test_server_transitions_are_exactly_the_spec_table(event: ServerEvent, status: Status) -> None:
    assert server_transition(status, event) == ALLOWED.get((event, status))


def test_terminal_statuses_accept_nothing() -> None:
    for status in TERMINAL:
        assert all(server_transition(status, event) is None for event in ServerEvent)
    assert server_transition(42, E.ACCEPT) is None  # not a status at all


def test_a_goal_canceled_before_it_was_accepted_is_recalled_and_an_accepted_one_preempted() -> None:
    walk = [S.PENDING]
    for event in (E.CANCEL_REQUEST, E.ACCEPT, E.CANCEL):
        nxt = server_transition(walk[-1], event)
        assert nxt is not None
        walk.append(nxt)
    assert walk == [S.PENDING, S.RECALLING, S.PREEMPTING, S.PREEMPTED]
    assert server_transition(S.RECALLING, E.CANCEL) == S.RECALLED


# ---------------------------------------------------------------- cancel (§9.2)

T1, T2, T3 = 1_000_000_000, 2_000_000_000, 3_000_000_000


@pytest.mark.parametrize(("cancel", "goal", "stamp", "hit"), [
    (CancelRequest("", 0), "a", T2, True),          # cancel all
    (CancelRequest("", 0), "b", 0, True),
    (CancelRequest("a", 0), "a", T2, True),         # that id
    (CancelRequest("a", 0), "b", T1, False),
    (CancelRequest("", T2), "b", T1, True),         # at and before the stamp
    (CancelRequest("", T2), "b", T2, True),
    (CancelRequest("", T2), "b", T3, False),
    (CancelRequest("a", T2), "a", T3, True),        # id and stamp combine
    (CancelRequest("a", T2), "b", T1, True),
    (CancelRequest("a", T2), "b", T3, False),
])
def test_cancel_matching(cancel: CancelRequest, goal: str, stamp: int, hit: bool) -> None:
    assert cancel.matches(goal, stamp) is hit


def test_a_cancel_for_an_unknown_id_is_remembered() -> None:
    assert CancelRequest("x", 0).remembers_unknown_id({"a"})
    assert not CancelRequest("a", 0).remembers_unknown_id({"a"})
    assert not CancelRequest("", 0).remembers_unknown_id(set())
    assert not CancelRequest("", T1).remembers_unknown_id(set())


def test_goals_stamped_before_the_last_cancel_are_canceled_on_arrival() -> None:
    assert canceled_by_last_cancel(T1, T2)
    assert canceled_by_last_cancel(T2, T2)
    assert not canceled_by_last_cancel(T3, T2)
    assert not canceled_by_last_cancel(0, T2)  # an unstamped goal gets "now"
    assert not canceled_by_last_cancel(T1, 0)


# ---------------------------------------------------------------- client CommState (§9.4)

NO, BAD = (), None
W = C.WAITING_FOR_RESULT
# status columns: PENDING ACTIVE PREEMPTED SUCCEEDED ABORTED REJECTED PREEMPTING RECALLING RECALLED
COLUMNS = [S.PENDING, S.ACTIVE, S.PREEMPTED, S.SUCCEEDED, S.ABORTED, S.REJECTED, S.PREEMPTING, S.RECALLING,
           S.RECALLED]
COMM_TABLE: dict[CommState, list[tuple[CommState, ...] | None]] = {
    C.WAITING_FOR_GOAL_ACK: [(C.PENDING,), (C.ACTIVE,), (C.ACTIVE, C.PREEMPTING, W), (C.ACTIVE, W), (C.ACTIVE, W),
                             (C.PENDING, W), (C.ACTIVE, C.PREEMPTING), (C.PENDING, C.RECALLING), (C.PENDING, W)],
    C.PENDING: [NO, (C.ACTIVE,), (C.ACTIVE, C.PREEMPTING, W), (C.ACTIVE, W), (C.ACTIVE, W), (W,),
                (C.ACTIVE, C.PREEMPTING), (C.RECALLING,), (C.RECALLING, W)],
    C.ACTIVE: [BAD, NO, (C.PREEMPTING, W), (W,), (W,), BAD, (C.PREEMPTING,), BAD, BAD],
    C.WAITING_FOR_RESULT: [BAD, NO, NO, NO, NO, NO, BAD, BAD, NO],
    C.WAITING_FOR_CANCEL_ACK: [NO, NO, (C.PREEMPTING, W), (C.PREEMPTING, W), (C.PREEMPTING, W), (W,),
                               (C.PREEMPTING,), (C.RECALLING,), (C.RECALLING, W)],
    C.RECALLING: [BAD, BAD, (C.PREEMPTING, W), (C.PREEMPTING, W), (C.PREEMPTING, W), (W,), (C.PREEMPTING,), NO,
                  (W,)],
    C.PREEMPTING: [BAD, BAD, (W,), (W,), (W,), BAD, NO, BAD, BAD],
    C.DONE: [BAD, BAD, NO, NO, NO, NO, BAD, BAD, NO],
}
CASES = [(state, status, row[i]) for state, row in COMM_TABLE.items() for i, status in enumerate(COLUMNS)]


@pytest.mark.parametrize(("state", "status", "steps"), CASES, ids=[f"{a.name}-{b.name}" for a, b, _ in CASES])
def test_comm_state_table(state: CommState, status: Status, steps: tuple[CommState, ...] | None) -> None:
    if steps is None:
        with pytest.raises(InvalidTransition):
            comm_steps(state, status)
    else:
        assert comm_steps(state, status) == steps


def test_unknown_status_codes_are_refused() -> None:
    with pytest.raises(ValueError):
        comm_steps(C.PENDING, 42)
    with pytest.raises(ValueError):
        comm_steps(C.PENDING, S.LOST)


@pytest.mark.parametrize("state", list(CommState), ids=lambda s: s.name)
def test_a_goal_missing_from_the_status_is_lost_unless_waiting_for_ack_or_result(state: CommState) -> None:
    keep = {C.WAITING_FOR_GOAL_ACK, C.WAITING_FOR_RESULT, C.DONE}
    assert lost_when_unlisted(state) is (state not in keep)


def test_a_full_goal_lifetime_walks_the_states_in_order() -> None:
    state, seen = C.WAITING_FOR_GOAL_ACK, []
    for status in (S.PENDING, S.ACTIVE, S.ACTIVE, S.SUCCEEDED):
        for step in comm_steps(state, status):
            seen.append(step)
            state = step
    assert seen == [C.PENDING, C.ACTIVE, W]


# ---------------------------------------------------------------- SimpleActionClient


@pytest.mark.parametrize(("simple", "comm", "step"), [
    (SimpleGoalState.PENDING, C.ACTIVE, SimpleStep(SimpleGoalState.ACTIVE, call_active=True)),
    (SimpleGoalState.PENDING, C.PREEMPTING, SimpleStep(SimpleGoalState.ACTIVE, call_active=True)),
    (SimpleGoalState.ACTIVE, C.ACTIVE, SimpleStep(SimpleGoalState.ACTIVE)),
    (SimpleGoalState.PENDING, C.RECALLING, SimpleStep(SimpleGoalState.PENDING)),
    (SimpleGoalState.PENDING, C.DONE, SimpleStep(SimpleGoalState.DONE, call_done=True)),
    (SimpleGoalState.ACTIVE, C.DONE, SimpleStep(SimpleGoalState.DONE, call_done=True)),
    (SimpleGoalState.PENDING, C.WAITING_FOR_RESULT, SimpleStep(SimpleGoalState.PENDING)),
    (SimpleGoalState.ACTIVE, C.WAITING_FOR_CANCEL_ACK, SimpleStep(SimpleGoalState.ACTIVE)),
])
def test_simple_state(simple: SimpleGoalState, comm: CommState, step: SimpleStep) -> None:
    assert simple_step(simple, comm) == step


@pytest.mark.parametrize(("simple", "comm"), [
    (SimpleGoalState.DONE, C.ACTIVE), (SimpleGoalState.DONE, C.PREEMPTING), (SimpleGoalState.ACTIVE, C.RECALLING),
    (SimpleGoalState.DONE, C.RECALLING), (SimpleGoalState.DONE, C.DONE),
])
def test_simple_state_protocol_errors(simple: SimpleGoalState, comm: CommState) -> None:
    step = simple_step(simple, comm)
    assert step.error and step.state is simple and not (step.call_active or step.call_done)


# ---------------------------------------------------------------- goal ids


def test_goal_ids() -> None:
    assert client_goal_id("/act_client", 1, 1795311570, 666_400_000) == "/act_client-1-1795311570.666"
    assert client_goal_id("/c", 12, 5, 999_600_000) == "/c-12-6.000"
    assert generated_goal_id("/fibonacci", 3, 1795311570, 5) == "/fibonacci-3-1795311570.5"
