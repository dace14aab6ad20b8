//! Which tool is in the spindle and which pocket holds every other: the
//! changer's bookkeeping, apart from the handshake. On a random-pocket
//! changer a committed change swaps the spindle's tool into the pocket
//! the new tool came from (the tool table's pocket 0 is the spindle);
//! otherwise a tool always returns to its own pocket.

use gcodec_profile::Profile;

use super::ChangerTool;
use crate::tool_resolution::table_tool;

/// A tool of the table and where it is.
#[derive(Clone, Debug)]
struct Slot {
    number: u32,
    /// `None`: the tool table gives it no location.
    pocket: Option<u32>,
}

#[derive(Clone, Debug)]
pub(crate) struct Pockets {
    random: bool,
    tools: Vec<Slot>,
    spindle: Option<ChangerTool>,
}

impl Pockets {
    /// From the profile's tool table (`location` is the pocket; the first
    /// entry of a number counts). On a random changer the tool in pocket 0
    /// starts in the spindle, unless `initial` names another: that one is
    /// swapped in as a change would.
    pub(crate) fn new(profile: &Profile, random: bool, initial: Option<ChangerTool>) -> Self {
        let mut tools: Vec<Slot> = Vec::new();
        for tool in &profile.tools {
            let number = *tool.number.get_ref();
            if !tools.iter().any(|s| s.number == number) {
                tools.push(Slot {
                    number,
                    pocket: tool.location,
                });
            }
        }
        let management = profile.tool_change.tool_management_enabled;
        let in_pocket_zero = || {
            let slot = tools.iter().find(|s| s.pocket == Some(0))?;
            let tool = profile.tool(slot.number)?;
            Some(ChangerTool {
                number: slot.number,
                label: table_tool(tool, management).label,
            })
        };
        let spindle = if random { in_pocket_zero() } else { None };
        let mut pockets = Self {
            random,
            tools,
            spindle,
        };
        if let Some(initial) = initial {
            if random {
                pockets.commit(Some(initial));
            } else {
                pockets.spindle = Some(initial);
            }
        }
        pockets
    }

    pub(crate) fn spindle(&self) -> Option<&ChangerTool> {
        self.spindle.as_ref()
    }

    /// The pocket of tool `number` (0 for the spindle's on a random
    /// changer).
    pub(crate) fn pocket_of(&self, number: u32) -> Option<u32> {
        self.tools
            .iter()
            .find(|s| s.number == number)
            .and_then(|s| s.pocket)
    }

    /// The pocket a prepare names: the tool's; for no tool (an unload),
    /// where the spindle's tool will go.
    pub(crate) fn prep_pocket(&self, tool: Option<&ChangerTool>) -> Option<u32> {
        match tool {
            Some(tool) => self.pocket_of(tool.number),
            None if self.random => self.free_pocket(),
            None => self.spindle.as_ref().and_then(|t| self.pocket_of(t.number)),
        }
    }

    /// The lowest pocket from 1 that no tool holds.
    fn free_pocket(&self) -> Option<u32> {
        (1..=u32::MAX).find(|p| !self.tools.iter().any(|s| s.pocket == Some(*p)))
    }

    /// Whether `tool` (none for an unload) is what the spindle holds.
    pub(crate) fn holds(&self, tool: Option<&ChangerTool>) -> bool {
        match (tool, &self.spindle) {
            (Some(tool), Some(spindle)) => tool.number == spindle.number,
            (None, None) => true,
            _ => false,
        }
    }

    /// A committed change: `incoming` (none for an unload) is in the
    /// spindle. On a random changer the tool going out takes the pocket
    /// the incoming one leaves (the lowest free pocket when it had none),
    /// and the incoming one takes pocket 0.
    pub(crate) fn commit(&mut self, incoming: Option<ChangerTool>) {
        if self.random {
            let freed = match &incoming {
                Some(tool) => self.pocket_of(tool.number),
                None => None,
            }
            .or_else(|| self.free_pocket());
            if let Some(outgoing) = &self.spindle
                && let Some(slot) = self.tools.iter_mut().find(|s| s.number == outgoing.number)
            {
                slot.pocket = freed;
            }
            if let Some(tool) = &incoming
                && let Some(slot) = self.tools.iter_mut().find(|s| s.number == tool.number)
            {
                slot.pocket = Some(0);
            }
        }
        self.spindle = incoming;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tool(number: u32) -> ChangerTool {
        ChangerTool {
            number,
            label: format!("T{number}"),
        }
    }

    fn profile(tools: &[(u32, u32)]) -> Profile {
        let mut text = String::from("[machine]\nname = \"t\"\ncontrol = \"840d_sl\"\n");
        for (number, location) in tools {
            text.push_str(&format!(
                "[[tools]]\nnumber = {number}\nlocation = {location}\n"
            ));
        }
        gcodec_profile::load(&text).expect("loads")
    }

    fn table(p: &Pockets) -> Vec<(u32, Option<u32>)> {
        p.tools.iter().map(|s| (s.number, s.pocket)).collect()
    }

    #[test]
    fn a_random_changer_swaps_as_the_recorded_trace_shows() {
        let mut p = Pockets::new(&profile(&[(5, 0), (10, 3), (20, 7)]), true, None);
        assert_eq!(p.spindle(), Some(&tool(5)));
        p.commit(Some(tool(10)));
        assert_eq!(table(&p), [(5, Some(3)), (10, Some(0)), (20, Some(7))]);
        p.commit(Some(tool(20)));
        assert_eq!(table(&p), [(5, Some(3)), (10, Some(7)), (20, Some(0))]);
        p.commit(Some(tool(5)));
        assert_eq!(table(&p), [(5, Some(0)), (10, Some(7)), (20, Some(3))]);
    }

    #[test]
    fn an_unload_on_a_random_changer_goes_to_the_lowest_free_pocket() {
        let mut p = Pockets::new(&profile(&[(5, 0), (10, 1), (20, 3)]), true, None);
        assert_eq!(p.prep_pocket(None), Some(2));
        p.commit(None);
        assert_eq!(table(&p), [(5, Some(2)), (10, Some(1)), (20, Some(3))]);
        assert_eq!(p.spindle(), None);
    }

    #[test]
    fn without_random_a_tool_keeps_its_pocket() {
        let mut p = Pockets::new(&profile(&[(1, 1), (20, 7)]), false, None);
        assert_eq!(p.spindle(), None);
        p.commit(Some(tool(20)));
        assert_eq!(table(&p), [(1, Some(1)), (20, Some(7))]);
        assert_eq!(p.prep_pocket(None), Some(7));
        assert!(p.holds(Some(&tool(20))));
    }

    #[test]
    fn an_initial_tool_on_a_random_changer_is_swapped_in() {
        let p = Pockets::new(&profile(&[(5, 0), (10, 3)]), true, Some(tool(10)));
        assert_eq!(p.spindle(), Some(&tool(10)));
        assert_eq!(table(&p), [(5, Some(3)), (10, Some(0))]);
    }
}
