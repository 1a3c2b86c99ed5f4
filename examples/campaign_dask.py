"""A contact campaign on a Dask cluster (docs/study.md, Campaign).

With a scheduler address (``python examples/campaign_dask.py tcp://host:8786``) the surfaces
run on that cluster's workers; without one a ``distributed.LocalCluster`` with two worker
processes is started here. Results are written by this process as they arrive, into
``campaign-dask/`` (rerun to resume), and are identical to a local run with the same settings.
Run: ``python examples/campaign_dask.py`` (about 20 s).
"""

from __future__ import annotations

import sys

import numpy as np
from distributed import Client, LocalCluster

from glstat.study import CampaignSettings, load_results, run_campaign

settings = CampaignSettings(hurst=(0.0, 0.5, 1.0), n_surfaces=10, grid=256, n_terms=(6,), n_examples=0)

if __name__ == "__main__":
    address = sys.argv[1] if len(sys.argv) > 1 else None
    cluster = None
    if address is None:
        cluster = LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None)
        address = cluster.scheduler_address
    with Client(address, timeout="10s") as client:
        print(f"scheduler {address}, workers: {len(client.scheduler_info()['workers'])}")
        run = run_campaign(settings, "campaign-dask", executor=client.get_executor())
        print(f"{len(run.computed)} surfaces computed, {run.skipped} reused, {run.wall_time:.1f} s")
    if cluster is not None:
        cluster.close()
    results = load_results("campaign-dask", settings)
    for ih, h in enumerate(settings.hurst):
        rs = [results[(ih, 0, i)] for i in range(settings.n_surfaces)]
        mean_p = np.mean([r["mean_pressure"] for r in rs]) / 1e9
        print(f"H = {h:g}: mean contact pressure {mean_p:.1f} GPa, "
              f"{np.mean([r['n_asperities'] for r in rs]):.1f} asperities in contact per surface")
