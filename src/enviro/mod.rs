//! The environment programs of open L-systems, built in: what cpfg asks
//! of vlab's `honda81`, `chiba`, `clover`, `ecosystem` and `obcheck`
//! through pipes, computed here as they compute it (Měch & Prusinkiewicz,
//! "Visual models of plants interacting with their environment", 1996).
//!
//! The derivation (`crate::driver`) interprets the word, makes a
//! [`Query`] of each `?E` module, in the word's order, with what the
//! program would read of it, and hands the queries of one step to the
//! program's [`Pass::answer`]; each [`Answer`] is written back into its
//! module's parameters. A program keeps what it must from one step to
//! the next (clover's leaves); the others start afresh each step.
//!
//! Imports only the IR: the programs know queries, not words or turtles.

mod canopy;
mod circles;
mod density;
mod light;
mod obstacles;

use crate::ir::environment::{Environment, Program};

/// One `?E` module as the program reads it: its parameters and the
/// turtle's position, each as cpfg's text carried them (parameters
/// printed `%g`, the position with the `.e` file's format) and read back
/// as `f32`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Query {
    pub params: Vec<f32>,
    /// The position's values the format printed: three, or fewer (a
    /// program that needs three answers no query with fewer); empty when
    /// the position is not sent.
    pub position: Vec<f32>,
}

/// A query of one parameter at `at`, for the programs' tests.
#[cfg(test)]
fn query_at(param: f32, at: [f32; 3]) -> Query {
    Query {
        params: vec![param],
        position: at.to_vec(),
    }
}

/// A program's answer to one query: per parameter, the value it sets, or
/// `None` to leave the parameter as it is. Empty: no answer at all.
pub type Answer = Vec<Option<f32>>;

/// A running program: it answers the queries of one step at a time.
pub trait Pass {
    /// The answers to `queries` (one per query, in their order).
    fn answer(&mut self, queries: &[Query]) -> Vec<Answer>;
}

/// The program of `env`, started: what answers its queries step by step.
pub fn start(env: &Environment) -> Box<dyn Pass> {
    match &env.program {
        Program::Density(d) => Box::new(density::Honda81::new(d)),
        Program::Light(l) => Box::new(light::Chiba::new(l)),
        Program::Canopy(c) => Box::new(canopy::Clover::new(c)),
        Program::Circles(c) => Box::new(circles::Ecosystem::new(c)),
        Program::Obstacles(o) => Box::new(obstacles::Obcheck::new(o)),
    }
}

/// The first three values of `position` when it has three (what the
/// programs that need a point in space ask for).
fn point(q: &Query) -> Option<[f32; 3]> {
    match q.position[..] {
        [x, y, z, ..] => Some([x, y, z]),
        _ => None,
    }
}
