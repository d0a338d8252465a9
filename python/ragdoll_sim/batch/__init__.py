"""ragdoll_batch's modules: scenario files, counter-based draws, the runner, the results CSV,
the report, the command line (docs/batch.md). fanout.py sends chunks of runs to Dask.
"""
