"""Winding models: winder settings -> stresses in the roll."""
