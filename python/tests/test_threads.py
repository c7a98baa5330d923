# SPDX-License-Identifier: MIT
"""Calls from several threads on one Clusterer: serialised, no deadlock, no
lost point (the GIL is released while the engine works)."""

import threading

import numpy as np

import streamclust


def test_concurrent_insert_retrieve_and_accessors():
    sim = streamclust.simulate("mid360", "office", seconds=0.4, seed=2)
    c = streamclust.Clusterer(preset="carc-mid360")
    packets = np.array_split(np.arange(len(sim.t)), 40)
    errors = []

    def inserter(part):
        try:
            for idx in packets[part::2]:
                c.insert(np.ascontiguousarray(sim.xyz[idx]), np.ascontiguousarray(sim.t[idx]))
        except Exception as e:  # noqa: BLE001 - reported below
            errors.append(e)

    def reader():
        try:
            for _ in range(200):
                c.retrieve()
                _ = (c.offered, c.size, c.grid, c.calibrating)
        except Exception as e:  # noqa: BLE001
            errors.append(e)

    threads = [threading.Thread(target=inserter, args=(k,)) for k in range(2)] + \
              [threading.Thread(target=reader) for _ in range(2)]
    for th in threads:
        th.start()
    for th in threads:
        th.join(timeout=120)
    assert not any(th.is_alive() for th in threads), "a thread is stuck (deadlock)"
    assert not errors
    assert c.offered == len(sim.t)
