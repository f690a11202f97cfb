"""Which subscribers a stream waits for before it starts (no rclpy; the plant node asks the graph).

A simulated stream that starts before its reader has matched loses its first chunks. Counting
matched subscriptions is not enough: any other subscriber in the domain (a `record` of plant/*)
counts too, so the stream started before the windowing node had matched and the run showed no
estimates at all. The plant names the nodes it waits for and the signals each must read:

    windowing:a1,a2,angle_difference     the windowing node, on these three signals
    record                               a node named record, on every signal
    /line1/drive7/windowing:a1           an absolute name

A signal is ready when every named node has a subscription on its topic (the ROS graph names the
node of each endpoint) and the publisher has matched as many subscriptions as the graph shows
compatible ones (so the named node's is matched too, not only discovered).
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class WantedSubscriber:
    node: str                   # fully qualified node name, e.g. /windowing
    signals: tuple[str, ...]


def fully_qualified(name: str, namespace: str) -> str:
    """``name`` resolved against ``namespace`` ('/' + name at the root)."""
    if name.startswith("/"):
        return name
    return namespace.rstrip("/") + "/" + name


def parse_wanted(entries, namespace: str, signals) -> list[WantedSubscriber]:
    """The ``wait_for_subscribers`` parameter's entries; ValueError naming a bad entry."""
    signals = tuple(signals)
    wanted = []
    for entry in entries:
        entry = entry.strip()
        if not entry:
            continue
        node, _, listed = entry.partition(":")
        node = node.strip()
        if not node or node.endswith("/"):
            raise ValueError(f"wait_for_subscribers entry {entry!r} names no node; allowed: "
                             "'NODE' or 'NODE:SIGNAL,SIGNAL'")
        chosen = tuple(s.strip() for s in listed.split(",") if s.strip()) if listed else signals
        unknown = [s for s in chosen if s not in signals]
        if unknown or not chosen:
            raise ValueError(f"wait_for_subscribers entry {entry!r}: unknown signal "
                             f"{', '.join(unknown) or '(none listed)'}; allowed: "
                             f"{', '.join(signals)}")
        wanted.append(WantedSubscriber(fully_qualified(node, namespace), chosen))
    return wanted


@dataclass(frozen=True)
class TopicState:
    """What the graph shows of one signal's topic."""
    subscriber_nodes: frozenset     # fully qualified names of the nodes subscribed
    compatible: int                 # subscriptions whose QoS the publisher can serve
    matched: int                    # subscriptions the publisher has matched


def missing(wanted: list[WantedSubscriber], topics: dict) -> list[str]:
    """What is still missing, one phrase each ('/windowing on a1'); [] when the stream may start.
    ``topics``: {signal: TopicState}."""
    out = []
    for want in wanted:
        absent = [s for s in want.signals if want.node not in topics[s].subscriber_nodes]
        if absent:
            out.append(f"{want.node} on {', '.join(absent)}")
    for signal in sorted({s for want in wanted for s in want.signals}):
        state = topics[signal]
        if state.matched < state.compatible:
            out.append(f"{signal}: {state.matched} of {state.compatible} subscriptions matched")
    return out
