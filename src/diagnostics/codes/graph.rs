//! Diagnostic codes of object-instancing graphs (`E10xx`, `W10xx`): the
//! checks of [`crate::ir::graph`] that every front end reading a graph
//! reports (`front::graph::check`), whatever its notation.

use super::Code;

codes! { GRAPH;
    GRAPH_DIVERGENT = "E1001", "a cycle that does not shrink",
"An object-instancing graph with a cycle (`A -> … -> A`) describes an
object made of copies of itself. Such an object exists only when every
cycle shrinks what it places: the transforms along the cycle, composed,
must be contractive (Bekaert & Willems 1994, §2.1). A cycle whose composed
transform keeps some length or stretches it would place ever larger
copies, and its object has no limit. The message names the cycle and the
factor by which it stretches its longest direction.

Example:
    graph {
      axiom A
      A -> [scale 1.25](A)      <- stretches by 1.25: write `scale 0.8`
    }";

    GRAPH_BARE_TERMINAL = "E1002", "a terminal without a geometry",
"A symbol without a rule is a terminal: it is drawn as its geometry. When
a graph has geometries, every terminal must carry one (Bekaert & Willems
§2.2): a terminal without one would be drawn as nothing, which is most
often a symbol forgotten. (A graph with no geometry at all is a pure IFS,
drawn as the images of its bounding volume.)

Example:
    graph {
      axiom A
      A -> [scale 0.5](A) B     <- B: no rule and no geometry
      geometry A = sphere (0, 0, 0) 1
    }";

    GRAPH_SINGULAR = "W1003", "a singular transform",
"The transform flattens space: it maps every solid onto a plane, a line
or a point (a zero scale, a matrix of rank below three). What it places
has no thickness, and a ray would never meet it; the ray tracer thickens
it to 1/1000 of its largest extent. Barnsley's fern places its stem so,
on purpose; elsewhere it is most often a zero written for a small number.

Example:
    A -> [scale (0.5, 0.5, 0)](A)     <- a flat copy";

    GRAPH_UNREACHABLE = "W1004", "a symbol the axiom never reaches",
"No rule leads from the axiom to this symbol, so nothing places it: its
rule and geometry are never drawn. It is often a symbol left over from an
earlier version of the graph, or the axiom names the wrong symbol.

Example:
    graph {
      axiom A
      A -> [scale 0.5](A)
      B -> [scale 0.5](B)     <- nothing places B
    }";
}
