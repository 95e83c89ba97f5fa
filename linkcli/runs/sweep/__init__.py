"""Sweeps over the driver: a range of driver values solved block by block, in vectorised passes.

``blocks`` holds the sweep, its reports and its output.
"""
