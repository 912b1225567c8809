//! `--camera-script`: camera input for scripted runs, one step per frame, through the same
//! [`FlyInput`] the keyboard and mouse produce.
//!
//! Steps are separated by commas or spaces: `w`, `a`, `s`, `d` (forward, left, back, right),
//! `q`, `e` (down, up), `look:DX:DY` (mouse motion in pixels, x right, y down), `wheel:N`
//! (notches), `reset`, `-` (no input); `STEP*N` repeats a step for N frames. Example:
//! `w*5,look:80:0*3,d*2`.
use super::camera::FlyInput;

/// The longest script (frames) accepted.
const MAX_STEPS: usize = 100_000;

/// Parses a camera script into one input per frame.
pub fn parse(script: &str) -> Result<Vec<FlyInput>, String> {
    let mut steps = Vec::new();
    for token in script.split([',', ' ']).filter(|t| !t.is_empty()) {
        let (step, count) = match token.rsplit_once('*') {
            Some((s, n)) => (
                s,
                n.parse::<usize>()
                    .map_err(|_| format!("'{token}': the repeat count '{n}' is not a number"))?,
            ),
            None => (token, 1),
        };
        let input = step_input(step).map_err(|m| format!("'{token}': {m}"))?;
        if steps.len() + count > MAX_STEPS {
            return Err(format!("more than {MAX_STEPS} steps"));
        }
        steps.extend(std::iter::repeat_n(input, count));
    }
    Ok(steps)
}

fn step_input(step: &str) -> Result<FlyInput, String> {
    let mut input = FlyInput::default();
    let number = |s: &str| {
        s.parse::<f32>()
            .ok()
            .filter(|v| v.is_finite() && v.abs() <= 1e4)
            .ok_or_else(|| format!("'{s}' is not a number in [-10000, 10000]"))
    };
    match step.split(':').collect::<Vec<_>>().as_slice() {
        ["w"] => input.forward = 1.0,
        ["s"] => input.forward = -1.0,
        ["d"] => input.right = 1.0,
        ["a"] => input.right = -1.0,
        ["e"] => input.up = 1.0,
        ["q"] => input.up = -1.0,
        ["reset"] => input.reset = true,
        ["-"] => {}
        ["look", dx, dy] => input.look = (number(dx)?, number(dy)?),
        ["wheel", n] => input.wheel = number(n)?,
        _ => {
            return Err(
                "not a step (w, a, s, d, q, e, look:DX:DY, wheel:N, reset, -, each with an \
                 optional *N)"
                    .into(),
            )
        }
    }
    Ok(input)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_repeat_and_combine() {
        let s = parse("w*2, look:10:-5,reset").unwrap();
        assert_eq!(s.len(), 4);
        assert_eq!(s[0].forward, 1.0);
        assert_eq!(s[1], s[0]);
        assert_eq!(s[2].look, (10.0, -5.0));
        assert!(s[3].reset);
        assert!(parse("").unwrap().is_empty());
    }

    #[test]
    fn bad_steps_are_errors() {
        for bad in ["x", "w*a", "look:1", "wheel:nan", "look:1:1e9", "w*200000"] {
            assert!(parse(bad).is_err(), "{bad}");
        }
    }
}
