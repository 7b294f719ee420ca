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
