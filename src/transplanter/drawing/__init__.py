"""The one drawing convention of every part any command draws (``sheet``): DXF in millimetres, the same
eight layers with a colour each, a title block, and byte-identical files across runs; gears (``gear_sheet``)
and plates with holes (``plate_sheet``) drawn on it, and every sheet of a run in one PDF (``pdf``), a sheet
drawn on a page by ``sheet_page``."""
