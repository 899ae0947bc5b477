//! The bytes a serial link received and the scan loop has not taken yet
//! (the field-update link of every board): a ring filled from the UART's
//! receive interrupt, emptied between scans.
//!
//! A byte lasts 87 µs on a 115,200-baud line and a scan 10 ms or more:
//! the UART's own buffer (one byte on the STM32F411, 32 on the RP2040)
//! would overrun between scans.

use field_update::frame::MAX_FRAME;

/// Bytes the queue holds: a request's frame and more.
pub const CAPACITY: usize = 2 * MAX_FRAME;

/// Received bytes, first in first out.
pub struct RxQueue {
    bytes: [u8; CAPACITY],
    head: usize,
    len: usize,
}

impl RxQueue {
    /// An empty queue.
    pub const fn new() -> RxQueue {
        RxQueue {
            bytes: [0; CAPACITY],
            head: 0,
            len: 0,
        }
    }

    /// Adds `byte`; when the queue is full the byte is dropped: its frame
    /// then fails its CRC and the PC sends the request again.
    pub fn push(&mut self, byte: u8) {
        if self.len < CAPACITY {
            self.bytes[(self.head + self.len) % CAPACITY] = byte;
            self.len += 1;
        }
    }

    /// The oldest byte, taken out.
    pub fn pop(&mut self) -> Option<u8> {
        if self.len == 0 {
            return None;
        }
        let byte = self.bytes[self.head];
        self.head = (self.head + 1) % CAPACITY;
        self.len -= 1;
        Some(byte)
    }
}

impl Default for RxQueue {
    fn default() -> RxQueue {
        RxQueue::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bytes_come_out_in_order_across_the_ring_and_a_full_queue_drops_the_newest() {
        let mut queue = RxQueue::new();
        assert_eq!(queue.pop(), None);
        // Move the head so that the next bytes wrap around the ring.
        for i in 0..CAPACITY - 3 {
            queue.push(i as u8);
            assert_eq!(queue.pop(), Some(i as u8));
        }
        for i in 0..CAPACITY + 5 {
            queue.push((i % 251) as u8);
        }
        // The first CAPACITY bytes were kept, the 5 after them dropped.
        for i in 0..CAPACITY {
            assert_eq!(queue.pop(), Some((i % 251) as u8), "byte {i}");
        }
        assert_eq!(queue.pop(), None);
        queue.push(7);
        assert_eq!(queue.pop(), Some(7));
    }
}
