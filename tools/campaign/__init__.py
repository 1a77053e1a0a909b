"""Closed-loop Monte Carlo campaigns for every registered mission, on Dask (README "Campaigns")."""
