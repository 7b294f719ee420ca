"""A section of a Markdown document that one benchmark script owns, between the markers
"<!-- NAME-begin ..." and "<!-- NAME-end -->": replaced in place, or appended when absent."""


def write_section(doc, name, lines):
    """Writes `lines` (the section, markers included) into the file `doc`."""
    text = open(doc).read()
    begin, end = "<!-- %s-begin" % name, "<!-- %s-end -->" % name
    if begin in text:
        a = text.index(begin)
        b = text.index(end) + len(end)
        text = text[:a] + "\n".join(lines) + text[b:]
    else:
        text = text.rstrip("\n") + "\n\n" + "\n".join(lines) + "\n"
    open(doc, "w").write(text)


def simulation_rows(path):
    """A `simulate --csv` file as {iteration: row}."""
    import csv

    with open(path) as f:
        return {int(r["iteration"]): r for r in csv.DictReader(f)}


def optional_cell(rows, iteration, column):
    """A column at one iteration to two decimals, or "-" where the CSV (an older build's) lacks it."""
    return "%.2f" % float(rows[iteration][column]) if column in rows[iteration] else "-"


def mean_edge_cells(rows):
    """The share of the cells shown that sat clamped at an edge of the box, the mean over the
    planes, or "-" where the CSV (an older build's) lacks it."""
    if "edge_cells" not in rows[1]:
        return "-"
    return "%.2f" % (sum(float(r["edge_cells"]) for r in rows.values()) / len(rows))
