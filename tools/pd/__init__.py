"""Ground tools of the pd module (mission HOLD): the table design (design.py), the C
boot tables (ctable.py), table images (image.py) and the SIL report (report.py)."""
