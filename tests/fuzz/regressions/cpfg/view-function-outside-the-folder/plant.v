angle increment: 45
function: ../../../../etc/passwd
