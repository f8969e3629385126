//! The page's analysis off its drawing thread: `web/worker.js` passes `[head, ...texts]` requests
//! and `[head, ...arrays]` replies (moved `ArrayBuffer`s, `swarf_analysis::wire`) to
//! [`swarf_analysis::Service`].

#[cfg(target_arch = "wasm32")]
mod worker {
    use js_sys::{Array, ArrayBuffer, Uint8Array};
    use swarf_analysis::{OpenFile, Reply, Service, wire};
    use wasm_bindgen::JsCast as _;
    use wasm_bindgen::prelude::*;

    /// The analysis side of the page: its messages in, the replies to post out.
    #[wasm_bindgen]
    #[derive(Default)]
    pub struct Analysis {
        service: Service,
        /// The other open files of the last job, which the page does not send again unchanged.
        files: Vec<OpenFile>,
    }

    #[wasm_bindgen]
    impl Analysis {
        /// Nothing analysed yet.
        #[wasm_bindgen(constructor)]
        pub fn new() -> Self {
            Self::default()
        }

        /// Takes a message of the page: the reply to post at once (a question's answer), or
        /// `undefined` (a job, whose replies come from [`Analysis::step`]). One that does not
        /// read throws, so the page analyses in its frames (this worker may lack texts it kept).
        pub fn handle(&mut self, message: &Array) -> Result<Option<Array>, JsError> {
            let head = bytes(&message.get(0));
            let texts = (1..message.length())
                .map(|i| String::from_utf8(bytes(&message.get(i))?).ok())
                .collect::<Option<Vec<_>>>();
            let request = head.zip(texts);
            let request = request.and_then(|(h, t)| wire::request_from(&h, t, &mut self.files));
            let request = request.ok_or_else(|| JsError::new("a message that does not read"))?;
            Ok(self.service.handle(request).map(|reply| parts(&reply)))
        }

        /// Whether an analysis is under way (and [`Analysis::step`] has work).
        pub fn busy(&self) -> bool {
            self.service.is_busy()
        }

        /// Runs a piece of the analysis under way: the reply to post (its progress, or its
        /// results), or `undefined` when there is none.
        pub fn step(&mut self) -> Option<Array> {
            self.service.step().map(|reply| parts(&reply))
        }
    }

    /// The bytes of an `ArrayBuffer`.
    fn bytes(value: &JsValue) -> Option<Vec<u8>> {
        let buffer = value.dyn_ref::<ArrayBuffer>()?;
        Some(Uint8Array::new(buffer).to_vec())
    }

    /// A reply as a message: its head and its arrays, each copied once into an `ArrayBuffer`
    /// that is then moved to the page.
    fn parts(reply: &Reply) -> Array {
        let (head, arrays) = wire::reply_parts(reply);
        std::iter::once(head.as_slice())
            .chain(arrays)
            .map(|bytes| Uint8Array::from(bytes).buffer())
            .collect()
    }
}
