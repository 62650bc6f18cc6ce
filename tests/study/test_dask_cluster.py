"""Studies on a real Dask cluster (a ``distributed.LocalCluster`` of two worker processes): the same table as on
local processes, and every case recorded once when a worker is killed mid-study."""
from __future__ import annotations

import os
import signal

import pytest

from tests.study.studies import gear_study, same_tables
from transplanter.study import run

distributed = pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def client():
    with (distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
          as cluster, distributed.Client(cluster) as client):
        yield client


@pytest.fixture(scope="module")
def local_table(tmp_path_factory):
    return run(gear_study(), tmp_path_factory.mktemp("local") / "out").rows


def test_a_dask_cluster_gives_the_table_of_local_processes(client, local_table, tmp_path):
    outcome = run(gear_study(), tmp_path / "out", executor=client)
    assert outcome.ran == 4 and same_tables(outcome.rows, local_table, tolerance=1e-9)


def test_a_worker_killed_mid_study_leaves_every_case_recorded_once(client, local_table, tmp_path):
    pids = client.run(os.getpid)
    killed = []

    def kill_a_worker(row):
        if not killed:
            os.kill(next(iter(pids.values())), signal.SIGKILL)
            killed.append(row["case_id"])

    outcome = run(gear_study(), tmp_path / "out", executor=client, on_case=kill_a_worker)
    assert killed and same_tables(outcome.rows, local_table, tolerance=1e-9)
    client.wait_for_workers(2, timeout=60)


def test_the_study_file_names_the_scheduler(client, local_table, tmp_path):
    spec = gear_study(vary=[{"field": "driver.eccentricity", "values": [0.3]},
                            {"field": "pair.teeth", "values": [30]}], executor={"scheduler": client.scheduler.address})
    outcome = run(spec, tmp_path / "out")
    assert outcome.ran == 1
    assert same_tables(outcome.rows, [row for row in local_table if row["case_id"] == outcome.rows[0]["case_id"]])
