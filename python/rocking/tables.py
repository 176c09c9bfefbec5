"""Markdown tables for the benchmarks' and studies' printed reports."""


def markdown(header, rows):
    """`header` and `rows` (lists of cells, any type) as a Markdown table with aligned columns."""
    rows = [[str(x) for x in r] for r in rows]
    header = [str(x) for x in header]
    widths = [max(len(x) for x in col) for col in zip(header, *rows)]

    def line(cells):
        return "| " + " | ".join(x.ljust(w) for x, w in zip(cells, widths)) + " |"

    rule = "|" + "|".join("-" * (w + 2) for w in widths) + "|"
    return "\n".join([line(header), rule] + [line(r) for r in rows])
