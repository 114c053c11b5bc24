//! Reading a check as a lesson file writes it (what follows `Check:`):
//! the one definition of the words docs/lessons.md documents.

use super::{
    ARRANGEMENTS, Check, Comparison, Condition, DIRECTIONS, Direction, LightsWanted, QUANTITIES, Quantity, RELATIONS,
    Relation, ShapeKind, ShapesWanted,
};

/// The check written `text` (what follows `Check:`), or what is wrong
/// with it.
pub(crate) fn parse(text: &str) -> Result<Check, String> {
    let text = text.trim();
    let words: Vec<&str> = text.split_whitespace().collect();
    match words.as_slice() {
        ["the", "scene", "depends", "on", "time"] => return Ok(Check::DependsOnTime),
        ["the", "scene", "matches", "the", "goal"] => return Ok(Check::MatchesGoal),
        ["procedure", ..] => return parse_procedure(text["procedure".len()..].trim()),
        _ => {}
    }
    let clauses: Vec<&str> = text.split(',').map(str::trim).collect();
    let (head, rest) = clauses.split_first().expect("split gives one part at least");
    let head_words: Vec<&str> = head.split_whitespace().collect();
    match head_words.as_slice() {
        ["camera", condition @ ..] => {
            let mut conditions = parse_conditions(rest)?;
            if !condition.is_empty() {
                conditions.insert(0, parse_condition(&condition.join(" "))?);
            }
            Ok(Check::Camera(conditions))
        }
        ["ambient", comparison @ ..] if rest.is_empty() => {
            Ok(Check::Ambient(parse_comparison(Quantity::Intensity, &comparison.join(" "))?))
        }
        ["number", name] if rest.is_empty() => Ok(Check::Number { name: name.to_string(), value: None }),
        ["number", name, comparison @ ..] if rest.is_empty() => {
            let value = parse_comparison(Quantity::X, &comparison.join(" "))?;
            Ok(Check::Number { name: name.to_string(), value: Some(value) })
        }
        ["object", name, "is", "a", kind] => {
            let (kind, _) = ShapeKind::read(kind).ok_or_else(|| format!("`{kind}` is not sphere, box or plane"))?;
            Ok(Check::Object { name: name.to_string(), kind, conditions: parse_conditions(rest)? })
        }
        [count, kind, more @ ..] => parse_parts(count, kind, &more.join(" "), rest),
        _ => Err(unknown_check()),
    }
}

fn unknown_check() -> String {
    "a check starts with `camera`, `ambient`, `a`, `an` or a count (`3 spheres`), `number`, `object`, \
     `procedure`, `the scene depends on time` or `the scene matches the goal`"
        .to_string()
}

/// `post(x)`: the procedure's name and its parameters.
fn parse_procedure(text: &str) -> Result<Check, String> {
    let usage = || "write a procedure as `procedure NAME(PARAMETER, ...)`".to_string();
    let (name, parameters) = text.strip_suffix(')').and_then(|t| t.split_once('(')).ok_or_else(usage)?;
    let name = name.trim();
    if name.is_empty() || name.contains(char::is_whitespace) {
        return Err(usage());
    }
    let parameters = parameters.split(',').filter(|p| !p.trim().is_empty()).count();
    Ok(Check::Procedure { name: name.to_string(), parameters })
}

/// `a light from above right`, `3 spheres like ball`, with the clauses after.
fn parse_parts(count: &str, kind: &str, first: &str, rest: &[&str]) -> Result<Check, String> {
    let count = match count {
        "a" | "an" | "one" => 1,
        number => number.parse::<usize>().ok().filter(|&n| n > 0).ok_or_else(unknown_check)?,
    };
    let clauses: Vec<&str> = std::iter::once(first).filter(|c| !c.is_empty()).chain(rest.iter().copied()).collect();
    if kind == "light" || kind == "lights" {
        let mut wanted = LightsWanted { count, from: Vec::new(), conditions: Vec::new(), weaker_than: None };
        for clause in clauses {
            if let Some(sides) = clause.strip_prefix("weaker than the light from ") {
                wanted.weaker_than = Some(parse_directions(sides)?);
            } else if let Some(sides) = clause.strip_prefix("from ") {
                wanted.from = parse_directions(sides)?;
            } else {
                wanted.conditions.push(parse_condition(clause)?);
            }
        }
        return Ok(Check::Lights(wanted));
    }
    let (kind, _) = ShapeKind::read(kind).ok_or_else(unknown_check)?;
    let mut wanted = ShapesWanted {
        count,
        kind,
        conditions: Vec::new(),
        like: None,
        moving: false,
        one_put: false,
        arrangement: Vec::new(),
    };
    for clause in clauses {
        if let Some(name) = clause.strip_prefix("like ") {
            wanted.like = Some(name.trim().to_string());
        } else if clause == "moving" {
            wanted.moving = true;
        } else if clause == "from one put" {
            wanted.one_put = true;
        } else if let Some((_, arrangement)) = ARRANGEMENTS.iter().find(|(name, _)| *name == clause) {
            wanted.arrangement.push(*arrangement);
        } else {
            wanted.conditions.push(parse_condition(clause)?);
        }
    }
    Ok(Check::Shapes(wanted))
}

fn parse_directions(text: &str) -> Result<Vec<Direction>, String> {
    let side = |word: &str| {
        DIRECTIONS
            .iter()
            .find(|(name, _)| *name == word)
            .map(|(_, d)| *d)
            .ok_or_else(|| format!("`{word}` is not a side: above, below, right, left, front or back"))
    };
    text.split_whitespace().filter(|w| *w != "and").map(side).collect()
}

fn parse_conditions(clauses: &[&str]) -> Result<Vec<Condition>, String> {
    clauses.iter().map(|clause| parse_condition(clause)).collect()
}

/// `radius 2`, `ks at least 0.3`, `color 255 120 40 within 60`.
fn parse_condition(clause: &str) -> Result<Condition, String> {
    let (name, comparison) = clause.trim().split_once(char::is_whitespace).unwrap_or((clause.trim(), ""));
    let Some(&(_, quantity, _)) = QUANTITIES.iter().find(|(known, _, _)| *known == name) else {
        let names: Vec<&str> = QUANTITIES.iter().map(|(name, _, _)| *name).collect();
        return Err(format!("`{name}` is not a property a check knows: {}", names.join(", ")));
    };
    Ok(Condition { quantity, comparison: parse_comparison(quantity, comparison)? })
}

/// `2`, `below 0.2`, `255 120 40 within 60`, for `quantity`.
fn parse_comparison(quantity: Quantity, text: &str) -> Result<Comparison, String> {
    let text = text.trim();
    let (relation, text) = RELATIONS
        .iter()
        .find_map(|(word, relation)| Some((*relation, text.strip_prefix(word)?.trim_start())))
        .unwrap_or((Relation::Equal, text));
    let (values, within) = match text.split_once(" within ") {
        Some((values, within)) => (values, Some(parse_number(within.trim())?)),
        None => (text, None),
    };
    let goal: Vec<f64> = values.split_whitespace().map(parse_number).collect::<Result<_, _>>()?;
    let name = quantity.name();
    match (goal.len(), quantity.arity()) {
        (1, 1) | (3, 3) => {}
        (_, 1) => return Err(format!("`{name}` takes one number")),
        _ => return Err(format!("`{name}` takes three numbers, with spaces between them")),
    }
    let within = within.unwrap_or_else(|| quantity.default_within(&goal));
    Ok(Comparison { relation, goal, within })
}

/// A number as a check writes it: `0.7`, `-3`, `pi/4`, `2*pi`, `-pi/2`.
pub(super) fn parse_number(text: &str) -> Result<f64, String> {
    let (sign, body) = match text.strip_prefix('-') {
        Some(body) => (-1.0, body),
        None => (1.0, text),
    };
    let factor = |word: &str| match word {
        "pi" => Some(std::f64::consts::PI),
        number => number.parse::<f64>().ok().filter(|n| n.is_finite()),
    };
    let (first, divisor) = match body.split_once('/') {
        Some((first, divisor)) => (first, factor(divisor)),
        None => (body, Some(1.0)),
    };
    let product = first.split('*').map(factor).try_fold(1.0, |product, f| Some(product * f?));
    match (product, divisor) {
        (Some(product), Some(divisor)) if divisor != 0.0 => Ok(sign * product / divisor),
        _ => Err(format!("`{text}` is not a number (numbers are like 0.7, -3, pi/4, 2*pi)")),
    }
}
