"""Ground tools of the @module@ module (mission @MISSION@): the table design (design.py), the C
boot tables (ctable.py), table images (image.py) and the SIL report (report.py)."""
