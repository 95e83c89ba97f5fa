"""The limits of the motion: extremes of a quantity over the driver's range, strokes, time ratios.

``search`` finds the extremes as the zeros of the quantity's rate over the driver.
"""
