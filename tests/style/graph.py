"""Cycles of a dependency graph between files, and between their folders (shared by
include_cycles.py and call_cycles.py; standard library only).

A graph is a dict: node -> {successor: evidence}, where evidence is a sorted list of strings that
say why the edge exists (the include line, the symbols used). A cycle is a strongly connected
component of more than one node; each is reported with its members and one concrete cycle through
them, each step with its evidence, so that a reader can go straight to the line to change.
"""


def add_edge(graph, a, b, why):
    """Edge a -> b with one more piece of evidence (a != b; self-edges are no cycle between files)."""
    if a == b:
        return
    graph.setdefault(a, {}).setdefault(b, set()).add(why)
    graph.setdefault(b, {})


def folder_graph(graph, folder_of):
    """The graph between folders: an edge F -> G (F != G) for every file edge a -> b with a in F,
    b in G; its evidence names the file edges that make it."""
    folders = {}
    for a, succ in graph.items():
        folders.setdefault(folder_of(a), {})
        for b, why in succ.items():
            fa, fb = folder_of(a), folder_of(b)
            if fa != fb:
                add_edge(folders, fa, fb, "%s -> %s (%s)" % (a, b, ", ".join(sorted(why))))
    return folders


def components(graph):
    """Strongly connected components of more than one node, each a sorted list, in sorted order
    (Tarjan's algorithm, iterative so that no recursion limit applies)."""
    index, low, on_stack, stack, found = {}, {}, set(), [], []
    counter = 0
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            node, successors = work[-1]
            advanced = False
            for succ in successors:
                if succ not in index:
                    index[succ] = low[succ] = counter
                    counter += 1
                    stack.append(succ)
                    on_stack.add(succ)
                    work.append((succ, iter(sorted(graph[succ]))))
                    advanced = True
                    break
                if succ in on_stack:
                    low[node] = min(low[node], index[succ])
            if advanced:
                continue
            work.pop()
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[node])
            if low[node] == index[node]:
                members = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    members.append(member)
                    if member == node:
                        break
                if len(members) > 1:
                    found.append(sorted(members))
    return sorted(found)


def one_cycle(graph, members):
    """A shortest cycle through the first member, inside the component (breadth-first search);
    the list of nodes with the first one repeated at the end."""
    inside = set(members)
    start = members[0]
    parent = {start: None}
    queue = [start]
    for node in queue:
        for succ in sorted(graph[node]):
            if succ not in inside:
                continue
            if succ == start:
                path = [node]
                while parent[path[-1]] is not None:
                    path.append(parent[path[-1]])
                return list(reversed(path)) + [start]
            if succ not in parent:
                parent[succ] = node
                queue.append(succ)
    raise AssertionError("a strongly connected component without a cycle through " + start)


def report(graph, what, out):
    """Print every cycle of graph (what: 'files' or 'folders', said in each line) to out as:
        cycle between WHAT (N): A, B, C
          A -> B: evidence; evidence          (one cycle through A)
          B -> A: ...
          also B -> C: evidence               (the other edges inside the component, so that
          ...                                  each of them can be judged: every one is a
                                               candidate to cut)
    Returns the number of cycles."""
    cycles = components(graph)
    for members in cycles:
        out.write("cycle between %s (%d): %s\n" % (what, len(members), ", ".join(members)))
        path = one_cycle(graph, members)
        steps = set(zip(path, path[1:]))
        for a, b in zip(path, path[1:]):
            out.write("  %s -> %s: %s\n" % (a, b, "; ".join(sorted(graph[a][b]))))
        inside = set(members)
        for a in members:
            for b in sorted(graph[a]):
                if b in inside and (a, b) not in steps:
                    out.write("  also %s -> %s: %s\n" % (a, b, "; ".join(sorted(graph[a][b]))))
    return len(cycles)
